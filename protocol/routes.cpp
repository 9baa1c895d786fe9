#include "protocol/routes.h"

namespace vesper::protocol {

std::string_view to_string(Method m) {
  switch (m) {
    case Method::Get:
      return "GET";
    case Method::Head:
      return "HEAD";
    case Method::Post:
      return "POST";
    case Method::Put:
      return "PUT";
  }
  return "?";
}

std::string_view to_string(Role r) {
  switch (r) {
    case Role::None:
      return "none";
    case Role::Submitter:
      return "submitter";
    case Role::Worker:
      return "worker";
    case Role::Either:
      return "either";
  }
  return "?";
}

std::string full_path(const Route& r) {
  return r.scope == Scope::Api ? api(r.path) : std::string(r.path);
}

}  // namespace vesper::protocol
