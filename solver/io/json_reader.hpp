// Checked reading of JSON objects: every accessor validates type and range and, on failure,
// throws InputError naming the file, the JSON path (RFC 6901 pointer) and the rule broken.
// `finish()` rejects keys that were never read, so a typo in a key is an error, not a silent default.
#pragma once
#include <functional>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace sc {

using json = nlohmann::json;

/// Reads a JSON file; a missing file or a syntax error becomes an InputError.
json read_json_file(const std::string& path);

class JsonObject {
 public:
  JsonObject(const json& j, std::string path, std::string file);

  bool has(const std::string& key) const { return j_->contains(key); }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::string path_of(const std::string& key) const { return path_ + "/" + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& rule) const;

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  double non_negative(const std::string& key, double fallback);
  /// A number in [lo, hi] (closed) or (lo, hi) (open_interval = true).
  double in_range(const std::string& key, double lo, double hi, bool open_interval, double fallback);
  double in_range(const std::string& key, double lo, double hi, bool open_interval);
  long integer(const std::string& key, long lo, long hi);
  long integer(const std::string& key, long lo, long hi, long fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  std::string one_of(const std::string& key, std::initializer_list<const char*> allowed);
  std::string one_of(const std::string& key, std::initializer_list<const char*> allowed, const std::string& fallback);
  /// An array of exactly `size` numbers (size 0: any non-empty length).
  std::vector<double> numbers(const std::string& key, std::size_t size = 0);
  JsonObject object(const std::string& key);
  std::vector<JsonObject> objects(const std::string& key);
  /// The raw value, marked as read (for values whose shape depends on context).
  const json& raw(const std::string& key);

  /// Marks a key as read without reading it (it belongs to another reader).
  void mark_used(const std::string& key) { used_.insert(key); }

  /// Throws if the object holds a key that no accessor read.
  void finish() const;

 private:
  const json& get(const std::string& key);
  const json* j_;
  std::string path_, file_;
  std::set<std::string> used_;
};

}  // namespace sc
