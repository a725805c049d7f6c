#include "scene_file.h"

#include "input_error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace chainbench {
namespace {

using nlohmann::json;

// Collects problems with their JSON paths instead of stopping at the first.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  void problem(const std::string& path, const std::string& reason) {
    if (problems_.size() < kMaxProblems) problems_.push_back(source_ + ": " + path + ": " + reason);
    paths_.push_back(path);
    ++count_;
  }
  // Whether a problem was reported at `path`, at a part of it, or inside it.
  bool reported(const std::string& path) const {
    return std::any_of(paths_.begin(), paths_.end(), [&](const std::string& p) {
      return p.rfind(path, 0) == 0 || path.rfind(p, 0) == 0;
    });
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
    if (!v.is_number_integer()) {
      problem(path, std::string("must be a whole number, got ") +
                        (v.is_number() ? "a fraction" : type_name(v)));
      return false;
    }
    const bool is_unsigned = v.is_number_unsigned();
    const auto u = is_unsigned ? v.get<std::uint64_t>() : 0;
    const auto s = is_unsigned ? 0 : v.get<std::int64_t>();
    if ((is_unsigned && u > static_cast<std::uint64_t>(hi)) ||
        (!is_unsigned && (s < lo || s > hi))) {
      problem(path, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                        v.dump());
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

  bool string(const json& v, const std::string& path, std::string& out) {
    if (!v.is_string()) {
      problem(path, std::string("must be a string, got ") + type_name(v));
      return false;
    }
    out = v.get<std::string>();
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
  std::vector<std::string> paths_;
  std::size_t count_ = 0;
};

// Replays a parse with SAX events to learn where in the document the parser gave up: the DOM
// parser only says at which byte.
class PathTracker : public nlohmann::json_sax<json> {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& k) override {
    frames_.back().key = k;
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
        p += "[" + std::to_string(f.index) + "]";
      } else if (!f.key.empty()) {
        p += (p.empty() ? "" : ".") + f.key;
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
  };
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool open(bool array) {
    frames_.push_back({array, 0, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
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
               "restitution", "gravity_scale"});
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
  double v = 0.0;
  if (j.contains("friction") && r.number(j["friction"], at + ".friction", v)) b.friction = v;
  if (j.contains("restitution") && r.number(j["restitution"], at + ".restitution", v))
    b.restitution = v;

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
      r.problem(at + ".density", "must be > 0, got " + j["density"].dump());
    } else {
      b.mass = v * 4.0 * b.half_extents.x * b.half_extents.y;
    }
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double range
    PathTracker tracker;
    json::sax_parse(text, &tracker);
    throw InputError(
        source + ": " + tracker.path() + ": " +
        (tracker.error().empty() ? std::string("not valid JSON: ") + e.what() : tracker.error()));
  }
  Reader r(source);
  Scene s;
  if (!root.is_object()) {
    r.problem("(root)", std::string("must be an object, got ") + Reader::type_name(root));
    r.fail();
  }
  r.only_keys(root, "",
              {"schema", "name", "description", "gravity", "dt", "steps", "rotation", "friction",
               "restitution", "bodies", "drivers", "expect"});
  int schema = 1;
  if (root.contains("schema") && r.integer(root["schema"], "schema", 0, 1000, schema) &&
      schema != 1) {
    r.problem("schema", "this chainbench reads schema 1, got " + std::to_string(schema));
  }
  s.name = "scene";
  if (root.contains("name")) r.string(root["name"], "name", s.name);
  if (root.contains("description")) r.string(root["description"], "description", s.description);
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
        r.problem(at + ".name", "\"" + s.bodies[i].name + "\" already names bodies[" +
                                    std::to_string(by_name[s.bodies[i].name]) + "]");
      }
    }
  }
  auto body_ref = [&](const json& j, const std::string& path, std::size_t& out) {
    std::string name;
    if (!r.string(j, path, name)) return;
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      r.problem(path, "no body is named \"" + name + "\"");
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
        if (j.contains("velocity")) r.vec2(j["velocity"], at + ".velocity", d.velocity);
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
    } else {
      for (std::size_t i = 0; i < expect.size() && i < limits::kMaxBodies; ++i) {
        const std::string at = "expect[" + std::to_string(i) + "]";
        const json& j = expect[i];
        if (!j.is_object()) {
          r.problem(at, std::string("must be an object, got ") + Reader::type_name(j));
          continue;
        }
        r.only_keys(j, at, {"body", "center", "tolerance"});
        Expectation e;
        for (const char* required : {"body", "center", "tolerance"}) {
          if (!j.contains(required)) r.problem(at + "." + required, "is required");
        }
        if (j.contains("body")) body_ref(j["body"], at + ".body", e.body);
        if (j.contains("center")) r.vec2(j["center"], at + ".center", e.center);
        if (j.contains("tolerance")) r.number(j["tolerance"], at + ".tolerance", e.tolerance);
        s.expect.push_back(e);
      }
    }
  }
  // Range rules shared with the built-in scenes; a value that already failed its type check is
  // not reported twice.
  for (const SceneIssue& issue : validate(s)) {
    if (!r.reported(issue.path)) r.problem(issue.path, issue.reason);
  }
  if (!r.ok()) r.fail();
  return s;
}

Scene load_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read the file");
  return parse_scene(text.str(), path);
}

}  // namespace chainbench
