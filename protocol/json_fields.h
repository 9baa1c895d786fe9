#pragma once
// Internal to protocol/: a message is described once, as a table of (JSON
// key, member) pairs, and both to_json and from_json follow from the table.
//   required(key, &T::m): always written; reading throws when it is absent.
//   optional(key, &T::m): left out when it equals its empty value (T{}'s
//     "", 0, empty list, or an unset std::optional); when absent on reading
//     the member keeps its default.
// Not nlohmann's NLOHMANN_DEFINE_TYPE_* macros: they name keys after members
// (ours come from fields.h, once) and always write every key (the wire
// format leaves empty optional keys out). Not NLOHMANN_JSON_SERIALIZE_ENUM:
// it maps an unknown value silently to the first one; read_enum refuses it.
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>
#include <type_traits>

namespace vesper::protocol::detail {

template <class T, class M, bool Optional>
struct Field {
  const char* key;
  M T::*member;
};

template <class T, class M>
constexpr Field<T, M, false> required(const char* key, M T::*member) {
  return {key, member};
}
template <class T, class M>
constexpr Field<T, M, true> optional(const char* key, M T::*member) {
  return {key, member};
}

template <class M>
struct is_std_optional : std::false_type {};
template <class V>
struct is_std_optional<std::optional<V>> : std::true_type {};

template <class T, class M, bool Optional>
void write_field(nlohmann::json& j, const T& v, const Field<T, M, Optional>& f) {
  const M& value = v.*(f.member);
  if constexpr (is_std_optional<M>::value) {
    if (value) j[f.key] = *value;
  } else {
    if constexpr (Optional)
      if (value == M{}) return;
    j[f.key] = value;
  }
}

template <class T, class M, bool Optional>
void read_field(const nlohmann::json& j, T& v, const Field<T, M, Optional>& f) {
  if constexpr (Optional || is_std_optional<M>::value) {
    auto it = j.find(f.key);
    if (it == j.end()) return;
    if constexpr (is_std_optional<M>::value)
      v.*(f.member) = it->template get<typename M::value_type>();
    else
      it->get_to(v.*(f.member));
  } else {
    j.at(f.key).get_to(v.*(f.member));
  }
}

// Adds the fields of `v` to the object `j`.
template <class T, class... F>
void write_fields(nlohmann::json& j, const T& v, const std::tuple<F...>& fields) {
  if (!j.is_object()) j = nlohmann::json::object();
  std::apply([&](const auto&... f) { (write_field(j, v, f), ...); }, fields);
}

template <class T, class... F>
void read_fields(const nlohmann::json& j, T& v, const std::tuple<F...>& fields) {
  if (!j.is_object())
    throw nlohmann::json::type_error::create(
        302, std::string("expected an object, got ") + j.type_name(), &j);
  std::apply([&](const auto&... f) { (read_field(j, v, f), ...); }, fields);
}

// An enum written as one of `names` (indexed by the enum's value).
template <class E, size_t N>
void write_enum(nlohmann::json& j, E e, const char* const (&names)[N]) {
  j = names[size_t(e)];
}
template <class E, size_t N>
void read_enum(const nlohmann::json& j, E& e, const char* const (&names)[N]) {
  const std::string s = j.get<std::string>();
  for (size_t i = 0; i < N; ++i)
    if (s == names[i]) {
      e = E(i);
      return;
    }
  throw nlohmann::json::other_error::create(501, "unknown value '" + s + "'", &j);
}

}  // namespace vesper::protocol::detail

// Defines to_json and from_json of `Type` from its table of fields.
#define VESPER_JSON_FIELDS(Type, ...)                                        \
  void to_json(nlohmann::json& j, const Type& m) {                           \
    j = nlohmann::json::object();                                            \
    ::vesper::protocol::detail::write_fields(j, m, std::tuple{__VA_ARGS__}); \
  }                                                                          \
  void from_json(const nlohmann::json& j, Type& m) {                         \
    ::vesper::protocol::detail::read_fields(j, m, std::tuple{__VA_ARGS__});  \
  }
