#pragma once
// Input mutations for the fuzz driver (driver.cpp), deterministic for a
// given seed: byte-level edits (bit flips, inserts, deletes, duplicated
// ranges, splices with another input) and JSON-aware edits of a parsed
// document (a value replaced by a number at the edge of the double or int
// range — 1e400, -1e308, 2147483648, 1e-310 — by a string from the corpus's
// dictionary, an odd string, a value of the wrong type, deep nesting, or
// another node; keys removed, added or duplicated; arrays grown).
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace vesper::fuzz {

class Mutator {
 public:
  // `dictionary`: strings and keys worth trying (taken from the corpus).
  Mutator(uint64_t seed, std::vector<std::string> dictionary);

  // One to four stacked mutations of `input`; `others` are splice partners.
  std::string mutate(const std::string& input, const std::vector<std::string>& others);

  uint64_t next(uint64_t n) { return n == 0 ? 0 : rng_() % n; }

 private:
  std::string mutate_bytes(std::string s, const std::vector<std::string>& others);
  // Empty when `s` is not a JSON document the mutator can edit.
  std::string mutate_json(const std::string& s, const std::vector<std::string>& others);
  std::string raw_value();  // JSON text for a replacement value

  std::mt19937_64 rng_;
  std::vector<std::string> dictionary_;
};

// Every key and string value of the JSON documents in `inputs` (once each).
std::vector<std::string> json_dictionary(const std::vector<std::string>& inputs);

}  // namespace vesper::fuzz
