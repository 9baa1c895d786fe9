#include "protocol/routes.h"

namespace vesper::protocol {

namespace {
constexpr std::string_view kMethods[] = {"GET", "HEAD", "POST", "PUT", "DELETE"};  // by Method
constexpr std::string_view kRoles[] = {"none", "submitter", "worker", "either"};   // by Role
}  // namespace

std::string_view to_string(Method m) { return kMethods[size_t(m)]; }
std::string_view to_string(Role r) { return kRoles[size_t(r)]; }

std::string full_path(const Route& r) {
  return r.scope == Scope::Api ? api(r.path) : std::string(r.path);
}

}  // namespace vesper::protocol
