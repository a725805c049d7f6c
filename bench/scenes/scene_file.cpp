// SPDX-License-Identifier: MIT
#include "scenes/scene_file.h"

#include "scenes/scene_text.h"
#include "support/input_error.h"
#include "support/number_text.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace chainbench {
namespace {

// A JSON number as the messages write every number (support/number_text.h): a float exactly,
// an integer as its digits.
std::string number_text(const nlohmann::json& v) {
  return v.is_number_float() ? exact_number(v.get<double>()) : v.dump();
}

using nlohmann::json;

// The most bodies a no_overlap entry may name: its pairs are tested one by one at every state.
constexpr std::size_t kMaxSelected = 100;

// Collects problems with their JSON paths instead of stopping at the first.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  void problem(const std::string& path, const std::string& reason) {
    // A path or key of any length is echoed cut (cut_for_message).
    if (problems_.size() < kMaxProblems)
      problems_.push_back(source_ + ": " + cut_for_message(path) + ": " + reason);
    paths_.insert(path);
    ++count_;
  }
  // Whether a problem was reported at `path`, at a part of it (a prefix ending where a component
  // does), or inside it. Ordered set lookups, so that refusing n bad bodies takes n log n.
  bool reported(const std::string& path) const {
    const auto inside = paths_.lower_bound(path);
    if (inside != paths_.end() && inside->compare(0, path.size(), path) == 0) return true;
    const std::string_view whole(path);
    for (std::size_t k = 1; k < whole.size(); ++k) {
      if ((whole[k] == '.' || whole[k] == '[') && paths_.count(whole.substr(0, k)) > 0) return true;
    }
    return false;
  }
  bool ok() const { return count_ == 0; }
  [[noreturn]] void fail() const {
    std::string msg;
    for (const std::string& p : problems_)
      msg += (msg.empty() ? "" : "\n") + p;
    if (count_ > problems_.size())
      msg += "\n" + source_ + ": ... and " + std::to_string(count_ - problems_.size()) + " more";
    throw InputError(msg);
  }

  // Reports keys of `object` that are not in `allowed`.
  void only_keys(const json& object, const std::string& path,
                 std::initializer_list<const char*> allowed) {
    for (const auto& item : object.items()) {
      const std::string& key = item.key();
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
        std::string list;
        for (const char* a : allowed)
          list += (list.empty() ? "" : ", ") + std::string(a);
        problem(join(path, key), "unknown key (allowed: " + list + ")");
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  static const char* type_name(const json& v) {
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "a boolean";
    if (v.is_null()) return "null";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "a number";
  }

  bool number(const json& v, const std::string& path, double& out) {
    if (!v.is_number()) {
      problem(path, std::string("must be a number, got ") + type_name(v) +
                        (v.is_string() ? " (NaN and infinities are not numbers here)" : ""));
      return false;
    }
    out = v.get<double>();
    if (!std::isfinite(out)) {
      problem(path, "must be a finite number (a value beyond double range was given)");
      return false;
    }
    return true;
  }

  bool integer(const json& v, const std::string& path, long long lo, long long hi, int& out) {
    // A whole number written as a float ("steps": 1e3, 1000.0) is that number, as --steps 1e3
    // is: JSON has one number type, and the file's writer may not have chosen the form.
    if (v.is_number_float()) {
      const double d = v.get<double>();
      const bool whole = std::isfinite(d) && d == std::floor(d);
      if (whole && d >= static_cast<double>(lo) && d <= static_cast<double>(hi)) {
        out = static_cast<int>(d);
        return true;
      }
    }
    if (!v.is_number_integer()) {
      // A whole number too large for 64 bits arrives as a float.
      const bool whole = v.is_number_float() && std::isfinite(v.get<double>()) &&
                         v.get<double>() == std::floor(v.get<double>());
      problem(path, whole ? "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "], got " + number_text(v)
                          : std::string("must be a whole number, got ") +
                                (v.is_number() ? number_text(v) : type_name(v)));
      return false;
    }
    const bool is_unsigned = v.is_number_unsigned();
    const auto u = is_unsigned ? v.get<std::uint64_t>() : 0;
    const auto s = is_unsigned ? 0 : v.get<std::int64_t>();
    if ((is_unsigned && u > static_cast<std::uint64_t>(hi)) ||
        (!is_unsigned && (s < lo || s > hi))) {
      problem(path, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                        number_text(v));
      return false;
    }
    out = static_cast<int>(is_unsigned ? static_cast<long long>(u) : s);
    return true;
  }

  bool vec2(const json& v, const std::string& path, Vec2d& out) {
    if (!v.is_array() || v.size() != 2) {
      problem(path, std::string("must be an array of two numbers, got ") + type_name(v) +
                        (v.is_array() ? " of " + std::to_string(v.size()) : ""));
      return false;
    }
    const bool x = number(v[0], path + "[0]", out.x);
    const bool y = number(v[1], path + "[1]", out.y);
    return x && y;
  }

  // A string field (scene_text.h): UTF-8 without control characters, at most max_bytes. `out`
  // is left as it was when the value is refused, so that no message echoes it.
  bool string(const json& v, const std::string& path, std::string& out,
              std::size_t max_bytes = kMaxSceneNameBytes, const char* what = "a name") {
    if (!v.is_string()) {
      problem(path, std::string("must be a string, got ") + type_name(v));
      return false;
    }
    const auto& text = v.get_ref<const std::string&>();
    if (const std::string why = scene_text_problem(text, max_bytes, what); !why.empty()) {
      problem(path, why);
      return false;
    }
    out = text;
    return true;
  }

  bool boolean(const json& v, const std::string& path, bool& out) {
    if (!v.is_boolean()) {
      problem(path, std::string("must be true or false, got ") + type_name(v));
      return false;
    }
    out = v.get<bool>();
    return true;
  }

  const std::string& source() const { return source_; }

 private:
  static constexpr std::size_t kMaxProblems = 50;
  std::string source_;
  std::vector<std::string> problems_;
  std::set<std::string, std::less<>> paths_;  // every path a problem was reported at
  std::size_t count_ = 0;
};

// Replays a parse with SAX events, knowing at each event where in the document it is: it tells
// where the parser gave up (the DOM parser only says at which byte), and finds keys given twice in
// one object, which the DOM parser silently keeps the last of.
class JsonWalk : public nlohmann::json_sax<json> {
 public:
  // With a reader, every key given twice is reported to it.
  explicit JsonWalk(Reader* duplicates = nullptr) : duplicates_(duplicates) {}
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& k) override {
    Frame& f = frames_.back();
    f.key = k;
    if (!f.keys.insert(k).second && duplicates_)
      duplicates_->problem(path(), "is given twice (one value per key)");
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string& token,
                   const nlohmann::detail::exception& e) override {
    // 406: a number the parser read but cannot hold, such as 1e999.
    error_ = e.id == 406
                 ? "number " + token + " is beyond double range, so it is not a finite number"
                 : std::string("not valid JSON: ") + e.what();
    return false;
  }
  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) {
        p.push_back('[');
        p.append(std::to_string(f.index));
        p.push_back(']');
      } else if (!f.key.empty()) {
        if (!p.empty()) p.push_back('.');
        p.append(f.key);
      }
    }
    return p.empty() ? "(root)" : p;
  }
  const std::string& error() const { return error_; }

 private:
  struct Frame {
    bool array;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;  // a set: an object of n keys is checked in n log n
  };
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool open(bool array) {
    frames_.push_back({array, 0, {}, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  Reader* duplicates_;
  std::vector<Frame> frames_;
  std::string error_;
};

void read_body(Reader& r, const json& j, const std::string& at, std::size_t index, SceneBody& b) {
  if (!j.is_object()) {
    r.problem(at, std::string("must be an object, got ") + Reader::type_name(j));
    return;
  }
  r.only_keys(j, at,
              {"name", "type", "center", "half_extents", "mass", "density", "velocity", "friction",
               "restitution", "gravity_scale", "penetration_tolerance", "from_step", "to_step",
               "category_bits", "mask_bits", "surface_velocity"});
  b.name = "body" + std::to_string(index);
  if (j.contains("name")) r.string(j["name"], at + ".name", b.name);
  std::string type;
  if (!j.contains("type")) {
    r.problem(at + ".type", "is required: static, kinematic or dynamic");
  } else if (r.string(j["type"], at + ".type", type)) {
    if (type == "static") {
      b.kind = BodyKind::kStatic;
    } else if (type == "kinematic") {
      b.kind = BodyKind::kKinematic;
    } else if (type == "dynamic") {
      b.kind = BodyKind::kDynamic;
    } else {
      r.problem(at + ".type", "must be static, kinematic or dynamic, got \"" + type + "\"");
    }
  }
  for (const char* required : {"center", "half_extents"}) {
    if (!j.contains(required)) r.problem(at + "." + required, "is required");
  }
  if (j.contains("center")) r.vec2(j["center"], at + ".center", b.center);
  if (j.contains("half_extents")) r.vec2(j["half_extents"], at + ".half_extents", b.half_extents);
  if (j.contains("velocity")) r.vec2(j["velocity"], at + ".velocity", b.velocity);
  if (j.contains("gravity_scale"))
    r.number(j["gravity_scale"], at + ".gravity_scale", b.gravity_scale);
  if (j.contains("from_step"))
    r.integer(j["from_step"], at + ".from_step", 0, limits::kMaxSteps, b.from_step);
  if (j.contains("to_step"))
    r.integer(j["to_step"], at + ".to_step", 1, limits::kMaxSteps, b.to_step);
  for (const auto& [key, bits] :
       {std::pair{"category_bits", &b.category_bits}, std::pair{"mask_bits", &b.mask_bits}}) {
    int value = 0;
    if (j.contains(key) && r.integer(j[key], at + "." + key, 0, 0xFFFF, value))
      *bits = static_cast<std::uint16_t>(value);
  }
  if (j.contains("surface_velocity") &&
      r.vec2(j["surface_velocity"], at + ".surface_velocity", b.surface_velocity)) {
    if (b.surface_velocity.y != 0.0) {
      r.problem(at + ".surface_velocity[1]",
                "must be 0: a belt runs along x, got " + number_text(j["surface_velocity"][1]));
    } else if (b.kind == BodyKind::kDynamic && b.surface_velocity.x != 0.0) {
      r.problem(at + ".surface_velocity",
                "is for static and kinematic bodies (conveyors), not a dynamic one");
    } else if (std::abs(b.surface_velocity.x) > 1e6) {
      r.problem(at + ".surface_velocity[0]",
                "must be within +-1e6 m/s, got " + number_text(j["surface_velocity"][0]));
    }
  }
  double v = 0.0;
  if (j.contains("friction") && r.number(j["friction"], at + ".friction", v)) b.friction = v;
  if (j.contains("restitution") && r.number(j["restitution"], at + ".restitution", v))
    b.restitution = v;
  if (j.contains("penetration_tolerance") &&
      r.number(j["penetration_tolerance"], at + ".penetration_tolerance", v))
    b.penetration_tolerance = v;

  const bool has_mass = j.contains("mass"), has_density = j.contains("density");
  if (b.kind != BodyKind::kDynamic) {
    if (has_mass || has_density)
      r.problem(at + (has_mass ? ".mass" : ".density"),
                "is for dynamic bodies only (a " + type + " body has infinite mass)");
  } else if (has_mass && has_density) {
    r.problem(at + ".density", "give mass or density, not both");
  } else if (!has_mass && !has_density) {
    r.problem(at + ".mass", "is required for a dynamic body (or give density)");
  } else if (has_mass) {
    r.number(j["mass"], at + ".mass", b.mass);
  } else if (r.number(j["density"], at + ".density", v)) {
    if (!(v > 0.0)) {
      r.problem(at + ".density", "must be > 0, got " + number_text(j["density"]));
    } else {
      b.mass = v * 4.0 * b.half_extents.x * b.half_extents.y;
    }
  }
}

// One bound vector of an expectation: [x, y] with null for an axis left free.
void read_bound(Reader& r, const json& v, const std::string& path, std::optional<double>& x,
                std::optional<double>& y) {
  if (!v.is_array() || v.size() != 2) {
    r.problem(path, std::string("must be an array of two numbers or nulls, got ") +
                        Reader::type_name(v) +
                        (v.is_array() ? " of " + std::to_string(v.size()) : ""));
    return;
  }
  std::optional<double>* out[2] = {&x, &y};
  for (std::size_t a = 0; a < 2; ++a) {
    double d = 0.0;
    if (!v[a].is_null() && r.number(v[a], path + "[" + std::to_string(a) + "]", d)) *out[a] = d;
  }
}

// The keys of a relation entry (above, below, on: the other body's name; squeezed: true) and of
// no_overlap's `bodies` selector.
void read_relation(Reader& r, const json& j, const std::string& at,
                   const std::unordered_map<std::string, std::size_t>& by_name, Expectation& e) {
  using Kind = Expectation::Kind;
  auto body_named = [&](const json& v, const std::string& path, std::size_t& out) {
    std::string name;
    if (!r.string(v, path, name)) return false;
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      r.problem(path, "no body is named \"" + cut_for_message(name) + "\"");
      return false;
    }
    out = it->second;
    return true;
  };
  if (e.kind == Kind::kNoOverlap) {
    if (!j.contains("bodies")) return;
    const json& v = j["bodies"];
    if (!v.is_array()) {
      r.problem(at + ".bodies",
                std::string("must be an array of body names, got ") + Reader::type_name(v));
      return;
    }
    if (v.size() > kMaxSelected) {
      r.problem(at + ".bodies", "names " + std::to_string(v.size()) + " bodies, more than " +
                                    std::to_string(kMaxSelected) +
                                    " (leave bodies out to check every pair)");
      return;
    }
    e.bodies.assign(v.size(), 0);
    for (std::size_t k = 0; k < v.size(); ++k)
      body_named(v[k], at + ".bodies[" + std::to_string(k) + "]", e.bodies[k]);
    if (v.size() < 2) r.problem(at + ".bodies", "must name at least two bodies");
    return;
  }
  if (j.contains("bodies"))
    r.problem(at + ".bodies", "belongs to no_overlap: a selector of the bodies whose pairs count");
  const char* key = to_string(e.kind);
  if (e.kind == Kind::kSqueezed) {
    bool yes = false;
    if (r.boolean(j[key], at + "." + key, yes) && !yes)
      r.problem(at + "." + key, "must be true (an entry states a fact that holds)");
  } else if (is_relation(e.kind)) {
    body_named(j[key], at + "." + key, e.other);
  }
  if (!is_relation(e.kind)) return;
  if (!j.contains("tolerance")) {
    r.problem(at + ".tolerance",
              std::string("is required with ") + key + ": the allowed distance, m");
  } else {
    r.number(j["tolerance"], at + ".tolerance", e.tolerance);
  }
}

// An `expect` entry states one fact: center or moved (with tolerance), min/max, at_rest,
// no_overlap (optionally among named bodies), above, below, on or squeezed (with tolerance).
void read_expectation(Reader& r, const json& j, const std::string& at,
                      const std::unordered_map<std::string, std::size_t>& by_name, Scene& s) {
  using Kind = Expectation::Kind;
  if (!j.is_object()) {
    r.problem(at, std::string("must be an object, got ") + Reader::type_name(j));
    return;
  }
  r.only_keys(j, at,
              {"body", "center", "moved", "tolerance", "min", "max", "at_rest", "no_overlap",
               "bodies", "above", "below", "on", "squeezed", "from_step", "to_step"});
  const bool center = j.contains("center"), moved = j.contains("moved");
  const bool bounds = j.contains("min") || j.contains("max");
  const bool at_rest = j.contains("at_rest"), no_overlap = j.contains("no_overlap");
  const bool above = j.contains("above"), below = j.contains("below"), on = j.contains("on");
  const bool squeezed = j.contains("squeezed");
  const int kinds = int{center} + int{moved} + int{bounds} + int{at_rest} + int{no_overlap} +
                    int{above} + int{below} + int{on} + int{squeezed};
  if (kinds == 0) {
    r.problem(at,
              "states nothing: give center or moved (with tolerance), min/max, at_rest, "
              "no_overlap, above, below, on or squeezed");
    return;
  }
  if (kinds > 1) {
    r.problem(at,
              "states more than one fact: give one of center, moved, min/max, at_rest, "
              "no_overlap, above, below, on, squeezed per entry (split it into several entries)");
    return;
  }
  Expectation e;
  e.kind = center       ? Kind::kCenter
           : moved      ? Kind::kMoved
           : bounds     ? Kind::kBounds
           : at_rest    ? Kind::kAtRest
           : no_overlap ? Kind::kNoOverlap
           : above      ? Kind::kAbove
           : below      ? Kind::kBelow
           : on         ? Kind::kOn
                        : Kind::kSqueezed;
  const bool relation = is_relation(e.kind);
  if (no_overlap) {
    if (j.contains("body"))
      r.problem(at + ".body", "no_overlap holds for every pair of bodies: remove body");
  } else if (!j.contains("body")) {
    r.problem(at + ".body", center || relation
                                ? "is required: the name of a body"
                                : "is required: the name of a body, or \"*\" for every "
                                  "dynamic body");
  } else {
    std::string name;
    if (r.string(j["body"], at + ".body", name)) {
      if (name == "*") {
        if (center) {
          r.problem(at + ".body", "\"*\" cannot have one expected centre: name a body");
        } else if (relation) {
          r.problem(at + ".body",
                    std::string("\"*\" cannot be ") + to_string(e.kind) + ": name a body");
        } else {
          e.body = Expectation::kEveryDynamic;
        }
      } else if (const auto it = by_name.find(name); it == by_name.end()) {
        r.problem(at + ".body", "no body is named \"" + cut_for_message(name) + "\"");
      } else {
        e.body = it->second;
      }
    }
  }
  if (center) r.vec2(j["center"], at + ".center", e.center);
  if (moved) r.vec2(j["moved"], at + ".moved", e.moved);
  if (center || moved) {
    if (!j.contains("tolerance")) {
      r.problem(at + ".tolerance", std::string("is required with ") +
                                       (center ? "center" : "moved") + ": the allowed distance, m");
    } else {
      r.number(j["tolerance"], at + ".tolerance", e.tolerance);
    }
  } else if (j.contains("tolerance") && !relation) {
    r.problem(at + ".tolerance",
              "belongs to center and moved, above, below, on and squeezed; min/max, at_rest and "
              "no_overlap carry their own limit");
  }
  read_relation(r, j, at, by_name, e);
  if (j.contains("min")) read_bound(r, j["min"], at + ".min", e.min_x, e.min_y);
  if (j.contains("max")) read_bound(r, j["max"], at + ".max", e.max_x, e.max_y);
  if (at_rest) r.number(j["at_rest"], at + ".at_rest", e.speed);
  if (no_overlap) r.number(j["no_overlap"], at + ".no_overlap", e.depth);
  int step = 0;
  if (j.contains("from_step") &&
      r.integer(j["from_step"], at + ".from_step", 0, limits::kMaxSteps, step)) {
    e.from_step = step;
  }
  if (j.contains("to_step") &&
      r.integer(j["to_step"], at + ".to_step", 0, limits::kMaxSteps, step)) {
    e.to_step = step;
  }
  s.expect.push_back(e);
}

// A driver's velocity: two numbers, or a number and null for an axis it leaves free (a walking
// character holds x and leaves y to gravity and contacts).
void driven_axes(Reader& r, const json& v, const std::string& path, Driver& d) {
  if (!v.is_array() || v.size() != 2) {
    r.problem(path, std::string("must be an array of two numbers (or null for a free axis), got ") +
                        Reader::type_name(v) +
                        (v.is_array() ? " of " + std::to_string(v.size()) : ""));
    return;
  }
  d.hold_x = !v[0].is_null();
  d.hold_y = !v[1].is_null();
  if (!d.hold_x && !d.hold_y) {
    r.problem(path, "holds neither axis: give at least one number");
    return;
  }
  if (d.hold_x) r.number(v[0], path + "[0]", d.velocity.x);
  if (d.hold_y) r.number(v[1], path + "[1]", d.velocity.y);
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  if (const std::string why = scene_bytes_problem(text); !why.empty()) {
    throw InputError(source + ": " + why);
  }
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double range
    JsonWalk tracker;
    json::sax_parse(text, &tracker);
    // The parser's message quotes what it last read, which may be bytes that are not UTF-8 or
    // megabytes of a string: shown escaped and cut, as every echoed input.
    const std::string why =
        tracker.error().empty() ? std::string("not valid JSON: ") + e.what() : tracker.error();
    throw InputError(source + ": " + cut_for_message(tracker.path()) + ": " +
                     cut_for_message(why, 400));
  }
  Reader r(source);
  Scene s;
  JsonWalk duplicates(&r);
  json::sax_parse(text, &duplicates);
  if (!root.is_object()) {
    r.problem("(root)", std::string("must be an object, got ") + Reader::type_name(root));
    r.fail();
  }
  r.only_keys(root, "",
              {"schema", "name", "description", "gravity", "dt", "steps", "rotation", "friction",
               "restitution", "bodies", "drivers", "expect", "penetration_tolerance"});
  int schema = 1;
  if (root.contains("schema") && r.integer(root["schema"], "schema", 0, 1000, schema) &&
      schema != 1) {
    r.problem("schema", "this chainbench reads schema 1, got " + std::to_string(schema));
  }
  s.name = "scene";
  if (root.contains("name")) r.string(root["name"], "name", s.name);
  if (root.contains("description")) {
    r.string(root["description"], "description", s.description, kMaxSceneDescriptionBytes,
             "a description");
  }
  if (root.contains("gravity")) r.vec2(root["gravity"], "gravity", s.gravity);
  if (root.contains("dt")) r.number(root["dt"], "dt", s.dt);
  if (root.contains("steps")) r.integer(root["steps"], "steps", 1, limits::kMaxSteps, s.steps);
  if (root.contains("rotation")) r.boolean(root["rotation"], "rotation", s.rotation);
  if (root.contains("friction")) r.number(root["friction"], "friction", s.friction);
  if (root.contains("restitution")) r.number(root["restitution"], "restitution", s.restitution);

  std::unordered_map<std::string, std::size_t> by_name;
  if (!root.contains("bodies")) {
    r.problem("bodies", "is required: an array of bodies");
  } else if (const json& bodies = root["bodies"]; !bodies.is_array()) {
    r.problem("bodies", std::string("must be an array, got ") + Reader::type_name(bodies));
  } else if (bodies.size() > limits::kMaxBodies) {
    r.problem("bodies", "holds " + std::to_string(bodies.size()) +
                            " bodies, more than the limit of " +
                            std::to_string(limits::kMaxBodies));
  } else {
    s.bodies.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::string at = "bodies[" + std::to_string(i) + "]";
      read_body(r, bodies[i], at, i, s.bodies[i]);
      if (!by_name.emplace(s.bodies[i].name, i).second) {
        // A name the reader gave (bodyN, for a body without one) says so: the user never wrote it.
        const std::size_t first = by_name[s.bodies[i].name];
        auto unnamed = [&](std::size_t k) {
          return bodies[k].is_object() && !bodies[k].contains("name");
        };
        const std::string name = "\"" + cut_for_message(s.bodies[i].name) + "\"";
        const std::string other = "bodies[" + std::to_string(first) + "]";
        if (unnamed(i)) {
          r.problem(at + ".name", "is not given, and its default " + name + " already names " +
                                      other + ": give this body a name");
        } else if (unnamed(first)) {
          r.problem(at + ".name",
                    name + " is already the default name of " + other +
                        ", which has no name of its own: give it one, or rename this");
        } else {
          r.problem(at + ".name", name + " already names " + other);
        }
      }
    }
  }
  auto body_ref = [&](const json& j, const std::string& path, std::size_t& out) {
    std::string name;
    if (!r.string(j, path, name)) return;
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      r.problem(path, "no body is named \"" + cut_for_message(name) + "\"");
    } else {
      out = it->second;
    }
  };

  if (root.contains("drivers")) {
    const json& drivers = root["drivers"];
    if (!drivers.is_array()) {
      r.problem("drivers", std::string("must be an array, got ") + Reader::type_name(drivers));
    } else if (drivers.size() > limits::kMaxDrivers) {
      r.problem("drivers", "holds more than " + std::to_string(limits::kMaxDrivers) + " drivers");
    } else {
      for (std::size_t i = 0; i < drivers.size(); ++i) {
        const std::string at = "drivers[" + std::to_string(i) + "]";
        const json& j = drivers[i];
        if (!j.is_object()) {
          r.problem(at, std::string("must be an object, got ") + Reader::type_name(j));
          continue;
        }
        r.only_keys(j, at, {"body", "kind", "velocity", "from_step", "to_step"});
        Driver d;
        d.to_step = s.steps;
        if (!j.contains("body"))
          r.problem(at + ".body", "is required: the name of the driven body");
        if (j.contains("body")) body_ref(j["body"], at + ".body", d.body);
        std::string kind = "velocity";
        if (j.contains("kind") && r.string(j["kind"], at + ".kind", kind) && kind != "velocity") {
          r.problem(at + ".kind",
                    "must be \"velocity\" (the only kind of driver), got \"" + kind + "\"");
        }
        if (!j.contains("velocity")) r.problem(at + ".velocity", "is required");
        if (j.contains("velocity")) driven_axes(r, j["velocity"], at + ".velocity", d);
        if (j.contains("from_step"))
          r.integer(j["from_step"], at + ".from_step", 0, limits::kMaxSteps, d.from_step);
        if (j.contains("to_step"))
          r.integer(j["to_step"], at + ".to_step", 0, limits::kMaxSteps, d.to_step);
        s.drivers.push_back(d);
      }
    }
  }
  if (root.contains("expect")) {
    const json& expect = root["expect"];
    if (!expect.is_array()) {
      r.problem("expect", std::string("must be an array, got ") + Reader::type_name(expect));
    } else if (expect.size() > limits::kMaxExpectations) {
      r.problem("expect",
                "holds more than " + std::to_string(limits::kMaxExpectations) + " entries");
    } else {
      for (std::size_t i = 0; i < expect.size(); ++i)
        read_expectation(r, expect[i], "expect[" + std::to_string(i) + "]", by_name, s);
    }
  }
  if (root.contains("penetration_tolerance")) {
    double v = 0.0;
    if (r.number(root["penetration_tolerance"], "penetration_tolerance", v))
      s.penetration_tolerance = v;
  }
  // Range rules shared with the built-in scenes; a value that already failed its type check is
  // not reported twice.
  for (const SceneIssue& issue : validate(s)) {
    if (!r.reported(issue.path)) r.problem(issue.path, issue.reason);
  }
  if (!r.ok()) r.fail();
  return s;
}

std::string set_run_length(Scene& scene, int steps, const std::string& source) {
  if (steps == scene.steps) return {};
  const int own = scene.steps;
  scene.steps = steps;
  // Checked before any entry is dropped, so that messages name entries as the file numbers them;
  // the entries to be dropped (those of the file's own last state) are not judged by the new
  // length.
  auto dropped_entry = [&](const std::string& path) {
    if (path.rfind("expect[", 0) != 0) return false;
    const std::size_t close = path.find(']');
    if (close == std::string::npos) return false;
    const std::size_t i = std::stoul(path.substr(7, close - 7));
    return i < scene.expect.size() && !scene.expect[i].windowed();
  };
  std::string problems;
  for (const SceneIssue& issue : validate(scene)) {
    if (dropped_entry(issue.path)) continue;
    problems += (problems.empty() ? "" : "\n") + source + ": " + issue.path + ": " + issue.reason +
                " (with --steps " + std::to_string(steps) + ")";
  }
  if (!problems.empty()) throw InputError(problems);
  const std::size_t before = scene.expect.size();
  std::vector<Expectation> kept;
  for (const Expectation& e : scene.expect) {
    if (e.windowed()) kept.push_back(e);
  }
  scene.expect = std::move(kept);
  const std::size_t dropped = before - scene.expect.size();
  if (dropped == 0) return {};
  return std::to_string(dropped) + " expectation(s) of " + source +
         " judge the state where bodies end, at step " + std::to_string(own) +
         "; the run ends at step " + std::to_string(steps) + ", so they are not checked";
}

std::string late_bodies_note(const Scene& scene, const std::string& source) {
  std::size_t late = 0;
  const SceneBody* first = nullptr;
  for (const SceneBody& b : scene.bodies) {
    if (b.from_step < scene.steps) continue;
    if (!first) first = &b;
    ++late;
  }
  if (late == 0) return {};
  return std::to_string(late) + " bod" + (late == 1 ? "y" : "ies") + " of " + source +
         " (the first \"" + first->name + "\", from_step " + std::to_string(first->from_step) +
         ") " + (late == 1 ? "enters" : "enter") + " after the run's last step, " +
         std::to_string(scene.steps) + ", and take" + (late == 1 ? "s" : "") + " part in nothing";
}

Scene load_scene_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw InputError(path + ": no such file");
  }
  if (status.type() == std::filesystem::file_type::directory) {
    throw InputError(path + ": is a directory, not a scene file");
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path + ": cannot open the file" +
                     (errno != 0 ? " (" + std::string(std::strerror(errno)) + ")" : ""));
  }
  // Read in pieces up to a bound, so that a device or a pipe with no end (/dev/zero) is refused
  // instead of filling memory. The most bodies a scene holds fit in far less.
  constexpr std::size_t kMaxBytes = 2'000'000'000;
  const auto too_big = [&] {
    return InputError(path + ": larger than 2 GB, more than a scene of " +
                      std::to_string(limits::kMaxBodies) +
                      " bodies (the most a scene holds) needs");
  };
  if (status.type() == std::filesystem::file_type::regular &&
      std::filesystem::file_size(path, ec) > kMaxBytes && !ec) {
    throw too_big();
  }
  std::string text;
  constexpr std::size_t kPiece = 1 << 20;
  while (in) {
    const std::size_t at = text.size();
    if (at > kMaxBytes) throw too_big();
    text.resize(at + kPiece);
    in.read(text.data() + at, static_cast<std::streamsize>(kPiece));
    text.resize(at + static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path + ": cannot read the file");
  return parse_scene(text, path);
}

}  // namespace chainbench
