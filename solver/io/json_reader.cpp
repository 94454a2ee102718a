#include "io/json_reader.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace sc {

namespace {

/// Watches the parser's events and rejects an object that names a key twice (RFC 8259 leaves the
/// meaning open; nlohmann keeps the last, which would hide a typo). Keeps the JSON path of the
/// value being read, so the error points at the object.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}

  bool operator()(int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: open(true); break;
      case json::parse_event_t::array_start: open(false); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end: frames_.pop_back(); break;
      case json::parse_event_t::key: add_key(parsed.get<std::string>()); break;
      case json::parse_event_t::value:
        if (!frames_.empty() && !frames_.back().object) ++frames_.back().count;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::string path;                  ///< JSON pointer of this object or array
    std::map<std::string, int> keys;   ///< key -> its position (1-based) in the object
    std::string last_key;
    int count = 0;                     ///< keys (object) or elements (array) seen so far
  };

  void open(bool object) {
    std::string path;
    if (!frames_.empty()) {
      Frame& parent = frames_.back();
      path = parent.path + "/" + (parent.object ? parent.last_key : std::to_string(parent.count++));
    }
    frames_.push_back({object, path, {}, {}, 0});
  }

  void add_key(const std::string& key) {
    Frame& f = frames_.back();
    const int position = ++f.count;
    const auto [it, inserted] = f.keys.emplace(key, position);
    if (!inserted)
      throw InputError(file_, f.path + "/" + key,
                       "duplicate key: \"" + key + "\" is key " + std::to_string(it->second) + " and again key " +
                           std::to_string(position) + " of " + (f.path.empty() ? "the document" : f.path) +
                           " (only one may be given)");
    f.last_key = key;
  }

  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "file cannot be opened (missing or unreadable)");
  std::stringstream buf;
  buf << in.rdbuf();
  try {
    return json::parse(buf.str(), DuplicateKeyCheck(path));
  } catch (const json::exception& e) {  // parse_error, or out_of_range for a number like 1e999
    throw InputError(path, "", std::string("not valid JSON: ") + e.what());
  }
}

JsonObject::JsonObject(const json& j, std::string path, std::string file)
    : j_(&j), path_(std::move(path)), file_(std::move(file)) {
  if (!j.is_object()) throw InputError(file_, path_.empty() ? "/" : path_, "must be a JSON object");
}

void JsonObject::fail(const std::string& key, const std::string& rule) const {
  throw InputError(file_, path_of(key), rule);
}

const json& JsonObject::get(const std::string& key) {
  if (!j_->contains(key)) fail(key, "required key is missing");
  used_.insert(key);
  return j_->at(key);
}

const json& JsonObject::raw(const std::string& key) { return get(key); }

double JsonObject::number(const std::string& key) {
  const json& v = get(key);
  if (!v.is_number()) fail(key, "must be a number, got " + std::string(v.type_name()));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  return x;
}
double JsonObject::number(const std::string& key, double fallback) { return has(key) ? number(key) : fallback; }

double JsonObject::positive(const std::string& key) {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be > 0, got " + json(x).dump());
  return x;
}
double JsonObject::positive(const std::string& key, double fallback) { return has(key) ? positive(key) : fallback; }

double JsonObject::non_negative(const std::string& key, double fallback) {
  if (!has(key)) return fallback;
  const double x = number(key);
  if (x < 0.0) fail(key, "must be >= 0, got " + json(x).dump());
  return x;
}

double JsonObject::in_range(const std::string& key, double lo, double hi, bool open_interval) {
  const double x = number(key);
  const bool ok = open_interval ? (x > lo && x < hi) : (x >= lo && x <= hi);
  if (!ok) {
    std::ostringstream rule;
    rule << "must lie in " << (open_interval ? "(" : "[") << lo << ", " << hi << (open_interval ? ")" : "]")
         << ", got " << json(x).dump();
    fail(key, rule.str());
  }
  return x;
}
double JsonObject::in_range(const std::string& key, double lo, double hi, bool open_interval, double fallback) {
  return has(key) ? in_range(key, lo, hi, open_interval) : fallback;
}

long JsonObject::integer(const std::string& key, long lo, long hi) {
  const json& v = get(key);
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + std::string(v.type_name()));
  const long x = v.get<long>();
  if (x < lo || x > hi) fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
  return x;
}
long JsonObject::integer(const std::string& key, long lo, long hi, long fallback) {
  return has(key) ? integer(key, lo, hi) : fallback;
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (!v.is_boolean()) fail(key, "must be true or false, got " + std::string(v.type_name()));
  return v.get<bool>();
}

std::string JsonObject::string(const std::string& key) {
  const json& v = get(key);
  if (!v.is_string()) fail(key, "must be a string, got " + std::string(v.type_name()));
  return v.get<std::string>();
}
std::string JsonObject::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

std::string JsonObject::one_of(const std::string& key, std::initializer_list<const char*> allowed) {
  const std::string s = string(key);
  std::string list;
  for (const char* a : allowed) {
    if (s == a) return s;
    list += (list.empty() ? "" : ", ") + std::string("\"") + a + "\"";
  }
  fail(key, "must be one of " + list + ", got \"" + s + "\"");
}
std::string JsonObject::one_of(const std::string& key, std::initializer_list<const char*> allowed,
                               const std::string& fallback) {
  return has(key) ? one_of(key, allowed) : fallback;
}

std::vector<double> JsonObject::numbers(const std::string& key, std::size_t size) {
  const json& v = get(key);
  if (!v.is_array()) fail(key, "must be an array of numbers, got " + std::string(v.type_name()));
  if (size != 0 && v.size() != size) fail(key, "must have exactly " + std::to_string(size) + " entries, got " + std::to_string(v.size()));
  if (v.empty()) fail(key, "must not be empty");
  std::vector<double> out;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
      throw InputError(file_, path_of(key) + "/" + std::to_string(k), "must be a finite number");
    out.push_back(v[k].get<double>());
  }
  return out;
}

JsonObject JsonObject::object(const std::string& key) { return JsonObject(get(key), path_of(key), file_); }

std::vector<JsonObject> JsonObject::objects(const std::string& key) {
  const json& v = get(key);
  if (!v.is_array()) fail(key, "must be an array of objects, got " + std::string(v.type_name()));
  std::vector<JsonObject> out;
  for (std::size_t k = 0; k < v.size(); ++k) out.emplace_back(v[k], path_of(key) + "/" + std::to_string(k), file_);
  return out;
}

void JsonObject::finish() const {
  for (const auto& [key, value] : j_->items())
    if (!used_.count(key) && key != "comment" && key.rfind("_", 0) != 0)
      throw InputError(file_, path_of(key), "unknown key (not part of the case format; see cases/README.md)");
}

}  // namespace sc
