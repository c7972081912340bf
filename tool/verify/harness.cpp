#include "verify/harness.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <type_traits>

#include "core/source.h"
#include "lang/tokens.h"
#include "shaderlib/shaderlib.h"
#include "verify/double_double.h"
#include "verify/kernel.h"
#include "verify/kernel_builder.h"
#include "verify/library_accuracy.h"
#include "verify/probes.h"
#include "verify/spirv.h"
#include "verify/worker.h"

namespace lwc {

namespace {

// A float32 HLSL kernel carries the file's own lines (verify/kernel_builder.h): its messages say
// where the function's code fails when the first names a real source (the file, an include).
bool kernel_says_where(const HarnessKernel& code, const CompileResult& kernel) {
  // The first message is the cause; later ones may be glslang recovering.
  if (!code.real_lines || kernel.messages.empty()) return false;
  const std::string& first = kernel.messages.front().source;
  return !first.empty() && first != "lwcport kernel" && first != "lwcport environment";
}

// Where a float64 reference still computes in float32 (a conversion to float outside the float32
// transcendental wrappers and the seeds of our double intrinsics: an intrinsic glslang narrows
// that verify/double_intrinsics does not cover), the first such line of the kernel, quoted; ""
// when it is float64 throughout.
std::string float32_in_reference(const std::vector<uint32_t>& spirv, std::string_view kernel_text) {
  for (const SpirvFunction& f : inspect_spirv(spirv).functions) {
    if (f.name.starts_with("lwc_f32_") || f.name.starts_with("lwc_d_") || f.narrowing_lines.empty()) continue;
    std::string_view line = kernel_text;
    for (int n = 1; n < f.narrowing_lines.front() && !line.empty(); ++n) line.remove_prefix(std::min(line.size(), line.find('\n') + 1));
    line = line.substr(0, line.find('\n'));
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    if (line.size() > 160) line = line.substr(0, utf8_char_start(line, 160));
    return fmt::format("the float64 reference would compute in float32: glslang converts a value to float in `{}` (`{}`); "
                       "no verdict is given against it", f.name, line);
  }
  return "";
}

// The number of a GLSL ES `#version NNN es` directive ("" for desktop GLSL or none).
std::string_view glsl_es_version(std::string_view text) {
  TokenText t(text);
  for (size_t i = 0; i < t.size(); ++i) {
    if (t.tokens[i].kind != Tok::directive) continue;
    Directive d = read_directive(t[i]);
    if (d.keyword != "version") continue;
    TokenText rest(d.rest);
    return rest.spells(1, {"es"}) ? rest[0] : std::string_view();
  }
  return {};
}

using Vec = std::array<double, 3>;
using Mat4 = std::array<double, 16>;  // column-major, column-vector convention: M * v

constexpr double kTile = 2097152.0;  // LWC_DF_TILE_SIZE

// ---- The scene of one invocation ------------------------------------------------------------

// Camera C, object origin T, the object's rotation-scale R, a local point L (world W = R L + T),
// a unit direction N and the view rotation V. Everything else derives from these, in double.
struct State {
  Vec camera{}, origin{}, local{}, direction{};
  Vec light{};  // a light near the object's point: a second absolute point (light code has two)
  std::array<double, 9> rotation_scale{};  // column-major 3x3
  std::array<double, 9> view{};
  bool edge = false;              // +-0, denormals, Inf, NaN: judged against what the original does
  bool non_finite = false;        // Inf / NaN inputs: drawn or not, the result must stay non-finite
  bool oversized_offset = false;  // tile/offset values carry an offset of several tiles
  Vec world() const {
    Vec w = origin;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) w[r] += rotation_scale[c * 3 + r] * local[c];
    return w;
  }
};

Mat4 affine(const std::array<double, 9>& m, const Vec& t) {
  Mat4 out{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) out[c * 4 + r] = m[c * 3 + r];
  out[12] = t[0], out[13] = t[1], out[14] = t[2], out[15] = 1;
  return out;
}
Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 out{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return out;
}
Mat4 translation(const Vec& t) { return affine({1, 0, 0, 0, 1, 0, 0, 0, 1}, t); }
std::array<double, 9> inverse3(const std::array<double, 9>& m) {
  auto at = [&](int r, int c) { return m[c * 3 + r]; };
  double det = at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) - at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
               at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  std::array<double, 9> out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      out[c * 3 + r] = (at(r1, c1) * at(r2, c2) - at(r1, c2) * at(r2, c1)) / det;
    }
  return out;
}
Mat4 inverse_affine(const std::array<double, 9>& m, const Vec& t) {
  std::array<double, 9> inv = inverse3(m);
  Vec it{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) it[r] -= inv[c * 3 + r] * t[c];
  return affine(inv, it);
}
std::array<double, 9> transpose3(const std::array<double, 9>& m) {
  std::array<double, 9> out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[r * 3 + c] = m[c * 3 + r];
  return out;
}
// Perspective, 90 degree field of view, near plane 10 cm, far plane at infinity (GL clip
// conventions): clip.w is the view depth, so an NDC error times w is a world-space offset.
Mat4 projection() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, -20, 0}; }

Vec neg(const Vec& v) { return {-v[0], -v[1], -v[2]}; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// splitmix64: a state is made per invocation, and seeding a Mersenne Twister (312 words) each time
// was a visible part of verify's host time.
class SplitMix {
 public:
  using result_type = uint64_t;
  explicit SplitMix(uint64_t seed) : state_(seed) {}
  static constexpr uint64_t min() { return 0; }
  static constexpr uint64_t max() { return ~uint64_t{0}; }
  uint64_t operator()() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

 private:
  uint64_t state_;
};

class Rng {
 public:
  explicit Rng(uint64_t seed) : g_(seed) {}
  double uniform(double lo = 0, double hi = 1) { return std::uniform_real_distribution<double>(lo, hi)(g_); }
  double sign() { return uniform() < 0.5 ? -1 : 1; }
  Vec unit() {
    Vec v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 1e-30;
    return {v[0] / n, v[1] / n, v[2] / n};
  }
  std::array<double, 9> rotation() {
    // Gram-Schmidt of two random directions.
    Vec a = unit(), b = unit();
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    b = {b[0] - d * a[0], b[1] - d * a[1], b[2] - d * a[2]};
    double n = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]) + 1e-30;
    b = {b[0] / n, b[1] / n, b[2] / n};
    Vec c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]};
  }

 private:
  SplitMix g_;
};

std::array<double, 9> scaled(std::array<double, 9> m, Vec s) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c * 3 + r] *= s[c];
  return m;
}

// A value as the sum of two floats, so every encoding (float, High + Low, tile + offset) starts
// from a value the pair holds exactly (LWC-BRIEF §6, reference hygiene).
double pair_exact(double v) {
  float hi = static_cast<float>(v);
  float lo = static_cast<float>(v - hi);
  return std::isfinite(v) && lo != 0 ? double(hi) + double(lo) : v;  // keeps -0, Inf and NaN as they are
}
Vec pair_exact(Vec v) { return {pair_exact(v[0]), pair_exact(v[1]), pair_exact(v[2])}; }

struct Case {
  std::string name;
  std::function<void(Rng&, State&)> make;
};

Vec near(Rng& r, const Vec& p, double lo, double hi) {
  Vec d = r.unit();
  double k = std::exp(r.uniform(std::log(lo), std::log(hi)));
  return {p[0] + d[0] * k, p[1] + d[1] * k, p[2] + d[2] * k};
}

const std::vector<Case>& cases() {
  static const std::vector<Case> list = [] {
    std::vector<Case> v;
    auto at = [](double m) { return [m](Rng& r, State& s) {
      s.camera = {m * r.sign(), m * 0.5 * r.uniform(-1, 1), m * 0.25 * r.uniform(-1, 1)};
      s.origin = near(r, s.camera, 1, 1000);
    }; };
    v.push_back({"origin", at(0)});
    v.push_back({"1e5 cm", at(1e5)});
    v.push_back({"2^20 cm", at(std::ldexp(1, 20))});
    v.push_back({"2^24 cm", at(std::ldexp(1, 24))});
    v.push_back({"2^31 cm", at(std::ldexp(1, 31))});
    v.push_back({"2^42 cm", at(std::ldexp(1, 42))});
    v.push_back({"2^43 - ulp cm", [](Rng& r, State& s) {
      double edge = std::ldexp(1, 43) - std::ldexp(1, 43 - 24);
      s.origin = {edge, r.uniform(-1000, 1000), r.uniform(-1000, 1000)};
      s.camera = near(r, s.origin, 1, 1000);
      s.camera[0] = std::min(s.camera[0], edge);
    }});
    v.push_back({"object 12.34 cm from a camera 2^42 cm away", [](Rng& r, State& s) {
      s.camera = {std::ldexp(1, 42), r.uniform(-1e6, 1e6), r.uniform(-1e6, 1e6)};
      Vec d = r.unit();
      s.origin = {s.camera[0] + 12.34 * d[0], s.camera[1] + 12.34 * d[1], s.camera[2] + 12.34 * d[2]};
      s.local = {0, 0, 0};
    }});
    for (double m : {1e6, std::ldexp(1, 30)})
      v.push_back({fmt::format("camera and object on opposite sides of the origin (+-{:g})", m), [m](Rng& r, State& s) {
        s.camera = {m, r.uniform(-100, 100), r.uniform(-100, 100)};
        s.origin = {-m, r.uniform(-100, 100), r.uniform(-100, 100)};
      }});
    v.push_back({"straddling 2^33 (2^33 - d, 2^33 + d')", [](Rng& r, State& s) {
      double top = std::ldexp(1, 33);
      s.camera = {top - r.uniform(0, 500), r.uniform(-100, 100), r.uniform(-100, 100)};
      s.origin = {top + r.uniform(0, 500), r.uniform(-100, 100), r.uniform(-100, 100)};
    }});
    for (double tile : {kTile, 262144.0})
      v.push_back({fmt::format("tile edges (k * {:g} +- 0.5)", tile), [tile](Rng& r, State& s) {
        double edge = std::floor(r.uniform(1, 4000)) * tile + 0.5 * r.sign();
        s.origin = {edge, edge, -edge};
        s.camera = near(r, s.origin, 1, 100);
        s.local = {0, 0, 0};
      }});
    v.push_back({"half-tile tie (2.5 * 2^21)", [](Rng& r, State& s) {
      s.origin = {2.5 * kTile, r.uniform(-100, 100), r.uniform(-100, 100)};
      s.camera = near(r, s.origin, 1, 100);
      s.local = {0, 0, 0};
    }});
    v.push_back({"FLWC offset larger than the tile size", [](Rng& r, State& s) {
      s.camera = {std::floor(r.uniform(1, 4000)) * kTile + r.uniform(-1e5, 1e5), r.uniform(-1e5, 1e5), r.uniform(-1e5, 1e5)};
      s.origin = near(r, s.camera, 1, 1000);
      s.oversized_offset = true;
    }});
    v.push_back({"+-0", [](Rng&, State& s) {
      s.edge = true;
      s.camera = {-0.0, 0.0, -0.0};
      s.origin = {0.0, -0.0, -0.0};
      s.local = {-0.0, -0.0, 0.0};
    }});
    v.push_back({"float32 denormals", [](Rng& r, State& s) {
      s.edge = true;
      s.camera = {0, 0, 0};
      s.origin = {r.sign() * 1e-40, r.sign() * 3e-39, r.sign() * 1.4e-45};
      s.local = {r.sign() * 1e-41, r.sign() * 1e-39, 0};
    }});
    v.push_back({"Inf input (object origin)", [](Rng& r, State& s) {
      s.edge = true;
      s.camera = {r.uniform(-1e5, 1e5), 0, 0};
      s.origin = {std::numeric_limits<double>::infinity() * r.sign(), 0, 0};
      s.non_finite = true;
    }});
    v.push_back({"NaN input (local position)", [](Rng& r, State& s) {
      s.edge = true;
      s.camera = {r.uniform(-1e5, 1e5), 0, 0};
      s.origin = near(r, s.camera, 1, 1000);
      s.local = {std::numeric_limits<double>::quiet_NaN(), 0, 0};
      s.non_finite = true;
    }});
    v.push_back({"log-uniform 1..2^43 cm", [](Rng& r, State& s) {
      for (double& c : s.camera) c = r.sign() * std::exp(r.uniform(0, 43 * std::log(2.0)));
      s.origin = near(r, s.camera, 1, 1e4);
    }});
    // Camera-to-object distances over every decade, 1 cm to the world's size (20 to 1000 km
    // included): what a planet-scale scene draws; each is judged only within the scene's view
    // distance.
    v.push_back({"camera-object distance log-uniform 1..2^43 cm", [](Rng& r, State& s) {
      double edge = std::ldexp(1, 43);
      for (double& c : s.camera) c = r.sign() * std::exp(r.uniform(0, 42 * std::log(2.0)));
      Vec d = r.unit();
      double k = std::exp(r.uniform(0, 43 * std::log(2.0)));
      for (int i = 0; i < 3; ++i) s.origin[i] = std::clamp(s.camera[i] + d[i] * k, -edge, edge);
    }});
    v.push_back({"ill-conditioned object matrix (scales 1e-4..1e4)", [](Rng& r, State& s) {
      s.camera = {std::ldexp(1, 31), 0, 0};
      s.origin = near(r, s.camera, 10, 1000);
      s.rotation_scale = scaled(r.rotation(), {std::pow(10, r.uniform(-4, 4)), std::pow(10, r.uniform(-4, 4)), std::pow(10, r.uniform(-4, 4))});
    }});
    v.push_back({"near-singular object matrix", [](Rng& r, State& s) {
      s.camera = {std::ldexp(1, 31), 0, 0};
      s.origin = near(r, s.camera, 10, 1000);
      s.rotation_scale = scaled(r.rotation(), {1, 1, 1e-6});
    }});
    return v;
  }();
  return list;
}

State make_state(size_t invocation) {
  const std::vector<Case>& all = cases();
  Rng r(0x9e3779b97f4a7c15ull ^ (invocation * 0x2545f4914f6cdd1dull));
  State s;
  s.rotation_scale = scaled(r.rotation(), {r.uniform(0.5, 2), r.uniform(0.5, 2), r.uniform(0.5, 2)});
  s.view = r.rotation();
  s.local = {r.uniform(-100, 100), r.uniform(-100, 100), r.uniform(-100, 100)};
  s.direction = r.unit();
  all[invocation % all.size()].make(r, s);
  s.camera = pair_exact(s.camera);
  s.origin = pair_exact(s.origin);
  s.light = pair_exact(near(r, s.world(), 50, 5000));
  return s;
}

// ---- What a name means ------------------------------------------------------------------------

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
bool has(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }
bool camera_word(const std::string& n) {
  return has(n, "camera") || has(n, "eye") || has(n, "viewpos") || has(n, "vieworigin") || has(n, "viewposition");
}

// What a value is (LWC-BRIEF terms), from its name: positions, matrices, directions.
enum class Role { camera, translated_camera, pre_view_translation, world_position, translated_position, object_origin,
                  light, translated_light,
                  local_position, direction, model, translated_model, world_to_local, model_normal, rotation_scale,
                  view, translated_view, view_projection, translated_view_projection, world_view_projection, projection,
                  world_plane, translated_plane, other };

// View members the engine hands over in translated world from UE 5.0 under their UE4 name
// (rules/world-space.json engine "view-members-translated-in-place"): their role in a variant
// built for `ue_version`, absolute before UE 5.0 and translated from it; none for another name.
std::optional<Role> in_place_role(const std::string& name, int ue_version) {
  bool ue5 = ue_version >= 500;
  if (name == "GlobalClippingPlane") return ue5 ? Role::translated_plane : Role::world_plane;
  if (name == "TranslucencyLightingVolumeMin") return ue5 ? Role::translated_position : Role::world_position;
  return std::nullopt;
}

Role role_of(const std::string& raw, int components) {
  std::string n = lower(raw);
  bool matrix = components >= 9;
  if (matrix) {
    if (has(n, "rotationscale") || has(n, "normalmatrix")) return has(n, "normal") ? Role::model_normal : Role::rotation_scale;
    if (has(n, "invtranspose") || has(n, "inversetranspose")) return Role::model_normal;
    if (has(n, "worldviewproj")) return Role::world_view_projection;
    if (has(n, "translatedworldtoclip") || has(n, "translatedviewproj")) return Role::translated_view_projection;
    if (has(n, "translatedworldtoview") || has(n, "translatedview")) return Role::translated_view;
    if (has(n, "worldtoclip") || has(n, "viewproj")) return Role::view_projection;
    if (has(n, "localtotranslatedworld")) return Role::translated_model;
    if (has(n, "worldtolocal")) return Role::world_to_local;
    if (has(n, "proj") || has(n, "viewtoclip")) return Role::projection;
    if (has(n, "view")) return Role::view;
    if (has(n, "world") || has(n, "model") || has(n, "localto")) return Role::model;
    return Role::other;
  }
  if (has(n, "previewtranslation")) return Role::pre_view_translation;
  // A plane (normal, distance) that points are dotted with as float4(P, 1).
  if (components == 4 && has(n, "plane")) return has(n, "translated") ? Role::translated_plane : Role::world_plane;
  if (camera_word(n)) return has(n, "translated") ? Role::translated_camera : Role::camera;
  if (has(n, "light") && (has(n, "pos") || has(n, "location"))) return has(n, "translated") ? Role::translated_light : Role::light;
  if (has(n, "translation")) return Role::object_origin;
  if (has(n, "normal") || has(n, "tangent") || has(n, "direction") || has(n, "dir")) return Role::direction;
  if (has(n, "relative") || has(n, "offset")) return Role::local_position;  // small by name: relative to something
  bool position = has(n, "pos") || has(n, "origin") || has(n, "location") || has(n, "referencepoint") || has(n, "point");
  if (position && has(n, "translated")) return Role::translated_position;
  if (position && (has(n, "world") || raw.ends_with("W") || has(n, "reference") || has(n, "origin"))) return Role::world_position;
  if (position || has(n, "local")) return Role::local_position;
  return Role::other;
}

// A value split by hand into float halves: `cameraHigh` / `cameraLow`, `positionHigh`, `high`.
enum class Half { none, high, low };
// A whole word only: `high`, `cameraHigh`, `position_low`, never `Yellow` or `Flow`.
std::pair<std::string, Half> split_half(const std::string& name, Encoding encoding) {
  if (encoding != Encoding::plain) return {name, Half::none};
  for (auto [words, half] : {std::pair{std::array{"high", "High", "_high"}, Half::high}, std::pair{std::array{"low", "Low", "_low"}, Half::low}})
    for (const char* word : words) {
      size_t base = name.size() - std::min(name.size(), std::strlen(word));
      bool whole_name_only = std::islower(static_cast<unsigned char>(word[0]));  // `high`, not `thigh`
      if (name.ends_with(word) && (base == 0 || !whole_name_only)) return {name.substr(0, base), half};
    }
  return {name, Half::none};
}

// The same tokens, whatever the layout: a fix that only removes a comment line moves the
// `#line`s and blank lines of the code after it, not the code.
bool same_code(const std::string& a, const std::string& b) {
  std::string plain_a = without_line_directives(a), plain_b = without_line_directives(b);
  TokenText ta(plain_a), tb(plain_b);
  if (ta.size() != tb.size()) return false;
  for (size_t i = 0; i < ta.size(); ++i)
    if (ta[i] != tb[i]) return false;
  return true;
}

// The role a world-space kind gives a result, where it says more than a name: a position (a
// function called `ShadowRayStart` returns a translated position). A `direction` may be a
// difference of positions, still in world units: there the name decides.
std::optional<Role> role_of_kind(Kind kind) {
  switch (kind) {
    case Kind::absolute: return Role::world_position;
    case Kind::translated: return Role::translated_position;
    case Kind::camera_offset: return Role::pre_view_translation;
    default: return std::nullopt;
  }
}

// An input's role: the world-space model's kind, where it has one, decides the family (absolute
// or translated world, the camera offset, a direction, which matrix), the name the member of it
// (the camera or an object's point); without a kind, the name alone.
Role role_for(const std::string& name, int components, std::optional<Kind> kind) {
  Role by_name = role_of(name, components);
  if (!kind || *kind == Kind::unknown) return by_name;
  auto keep = [&](std::initializer_list<Role> family, Role otherwise) {
    return std::find(family.begin(), family.end(), by_name) != family.end() ? by_name : otherwise;
  };
  bool matrix = components >= 9;
  switch (*kind) {
    case Kind::absolute: return matrix ? by_name : keep({Role::camera, Role::world_position, Role::object_origin, Role::light}, Role::world_position);
    case Kind::translated:
      return matrix ? by_name : keep({Role::translated_camera, Role::translated_position, Role::translated_light}, Role::translated_position);
    case Kind::camera_offset: return matrix ? by_name : Role::pre_view_translation;
    case Kind::direction: return matrix ? by_name : Role::direction;
    case Kind::local: return matrix ? by_name : keep({Role::local_position, Role::direction, Role::other}, Role::local_position);
    case Kind::world_matrix: return keep({Role::model, Role::world_view_projection}, Role::model);
    case Kind::translated_world_matrix: return Role::translated_model;
    case Kind::from_world_matrix: return keep({Role::view, Role::view_projection, Role::world_to_local}, Role::view_projection);
    case Kind::from_translated_matrix: return keep({Role::translated_view, Role::translated_view_projection}, Role::translated_view_projection);
    case Kind::rotation_matrix: return keep({Role::rotation_scale, Role::model_normal}, Role::rotation_scale);
    case Kind::local_matrix: return keep({Role::projection, Role::model_normal, Role::rotation_scale}, Role::projection);
    case Kind::unknown: break;
  }
  return by_name;
}

// What the model says an input is: a whole parameter's kind, a global's, or what the world-space
// data says of its path (engine members: `Parameters.WorldPosition_CamRelative` is translated).
// Naming conventions are left to the name.
std::optional<Kind> model_kind(const FunctionFacts& facts, const std::string& function, const Leaf& leaf) {
  const std::string& path = leaf.path;
  size_t member = path.find_first_of(".[");
  if (path.starts_with("lwc_p") && member == std::string::npos) {
    size_t index = 0;
    auto [end, error] = std::from_chars(path.data() + 5, path.data() + path.size(), index);
    auto kinds = facts.parameters.find(function);
    if (error == std::errc() && end == path.data() + path.size() && kinds != facts.parameters.end() && index < kinds->second.size() &&
        kinds->second[index] != Kind::unknown)
      return kinds->second[index];
  } else if (member == std::string::npos) {
    if (auto it = facts.globals.find(path); it != facts.globals.end() && it->second != Kind::unknown) return it->second;
  }
  if (!facts.world) return std::nullopt;
  Path segments;
  for (size_t at = 0; at <= path.size();) {
    size_t end = path.find('.', at);
    if (end == std::string::npos) end = path.size();
    std::string name = path.substr(at, end - at);
    name = name.substr(0, name.find('['));
    segments.push_back({name, false});
    at = end + 1;
  }
  for (const WorldData::Source& source : facts.world->sources)
    if (!source.by_name && source.pattern.matches(segments)) return source.kind;
  return std::nullopt;
}

// What a role is filled with, for `verify --explain`.
std::string_view role_text(Role role) {
  switch (role) {
    case Role::camera: return "the camera's absolute position";
    case Role::translated_camera: return "the camera in translated world (0)";
    case Role::pre_view_translation: return "minus the camera's position (PreViewTranslation)";
    case Role::world_position: return "an absolute world position (the object's point)";
    case Role::translated_position: return "the object's point relative to the camera";
    case Role::object_origin: return "the object's origin";
    case Role::light: return "a light's absolute position (0.5 to 50 m from the object's point)";
    case Role::translated_light: return "that light relative to the camera";
    case Role::local_position: return "a local position (within 100 cm of its origin)";
    case Role::direction: return "a unit direction";
    case Role::model: return "the object's local-to-world matrix";
    case Role::translated_model: return "the object's local-to-translated-world matrix";
    case Role::world_to_local: return "the object's world-to-local matrix";
    case Role::model_normal: return "the object's normal matrix";
    case Role::rotation_scale: return "the object's rotation and scale";
    case Role::view: return "the world-to-view matrix";
    case Role::translated_view: return "the translated-world-to-view matrix";
    case Role::view_projection: return "the world-to-clip matrix";
    case Role::translated_view_projection: return "the translated-world-to-clip matrix";
    case Role::world_view_projection: return "the local-to-clip matrix";
    case Role::projection: return "the projection (90 degrees)";
    case Role::world_plane: return "a plane through the object's origin, in absolute world (normal, distance)";
    case Role::translated_plane: return "that plane in translated world (a variant built for UE 5 reads the view's clipping plane so)";
    case Role::other: break;
  }
  return "a value in [0.25, 1], fixed per name";
}

bool world_units(Role r) {
  return r == Role::camera || r == Role::translated_camera || r == Role::pre_view_translation || r == Role::world_position ||
         r == Role::translated_position || r == Role::object_origin || r == Role::local_position || r == Role::light ||
         r == Role::translated_light;
}

double light_inverse_radius(const State& s) {
  Vec d = sub(s.light, s.world());
  return 1.0 / (4.0 * std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-30);
}

// The value of a role in `state`, as `components` doubles (matrices column-major, column-vector
// convention); a float4 position gets w = 1.
std::vector<double> role_value(Role role, int components, const State& s, uint64_t name_hash, size_t invocation) {
  auto vec = [&](const Vec& v, double w) {
    std::vector<double> out(v.begin(), v.end());
    out.resize(components, w);
    return out;
  };
  auto mat = [&](const Mat4& m) {
    if (components == 16) return std::vector<double>(m.begin(), m.end());
    std::vector<double> out;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) out.push_back(m[c * 4 + r]);
    out.resize(components, 0);
    return out;
  };
  // Built on demand: this runs for every input of every invocation.
  auto model = [&] { return affine(s.rotation_scale, s.origin); };
  auto rotation_only = [&] { return affine(s.view, {0, 0, 0}); };
  auto view = [&] { return multiply(rotation_only(), translation(neg(s.camera))); };
  switch (role) {
    case Role::camera: return vec(s.camera, 1);
    case Role::translated_camera: return vec({0, 0, 0}, 1);
    case Role::pre_view_translation: return vec(neg(s.camera), 0);
    case Role::world_position: return vec(s.world(), 1);
    case Role::translated_position: return vec(sub(s.world(), s.camera), 1);
    case Role::object_origin: return vec(s.origin, 1);
    // A float4 light carries its inverse radius in w (`LightPositionAndInvRadius`): a radius four
    // times the light's distance, so the attenuation it drives stays well inside (0, 1).
    case Role::light: return vec(s.light, light_inverse_radius(s));
    case Role::translated_light: return vec(sub(s.light, s.camera), light_inverse_radius(s));
    case Role::local_position: return vec(s.local, 1);
    case Role::direction: return vec(s.direction, 0);
    case Role::model: return mat(model());
    case Role::translated_model: return mat(affine(s.rotation_scale, sub(s.origin, s.camera)));
    case Role::world_to_local: return mat(inverse_affine(s.rotation_scale, s.origin));
    case Role::model_normal: return mat(affine(transpose3(inverse3(s.rotation_scale)), {0, 0, 0}));
    case Role::rotation_scale: return mat(affine(s.rotation_scale, {0, 0, 0}));
    case Role::view: return mat(view());
    case Role::translated_view: return mat(rotation_only());
    case Role::view_projection: return mat(multiply(projection(), view()));
    case Role::translated_view_projection: return mat(multiply(projection(), rotation_only()));
    case Role::world_view_projection: return mat(multiply(projection(), multiply(view(), model())));
    case Role::projection: return mat(projection());
    // Through the object's origin, facing the fixed direction: the same plane in either space.
    case Role::world_plane:
    case Role::translated_plane: {
      Vec at = role == Role::world_plane ? s.origin : sub(s.origin, s.camera);
      double length = std::sqrt(s.direction[0] * s.direction[0] + s.direction[1] * s.direction[1] + s.direction[2] * s.direction[2]);
      Vec normal = {s.direction[0] / length, s.direction[1] / length, s.direction[2] / length};
      return vec(normal, -(normal[0] * at[0] + normal[1] * at[1] + normal[2] * at[2]));
    }
    case Role::other: break;
  }
  // Anything else (fog parameters, colours): a value in [0.25, 1] by name, the same in every variant.
  std::vector<double> out;
  for (int i = 0; i < components; ++i) {
    uint64_t x = name_hash ^ (invocation * 0x9e3779b97f4a7c15ull) ^ (static_cast<uint64_t>(i) << 56);
    x ^= x >> 31, x *= 0xbf58476d1ce4e5b9ull, x ^= x >> 27;
    out.push_back(0.25 + 0.75 * static_cast<double>(x >> 11) * 0x1p-53);
  }
  return out;
}

// FNV-1a over a name's bytes or a SPIR-V module's words (identical kernels cost the same
// whatever the clock says).
template <typename Values>
uint64_t fnv1a(const Values& values) {
  uint64_t h = 1469598103934665603ull;
  for (auto v : values) h = (h ^ static_cast<std::make_unsigned_t<decltype(v)>>(v)) * 1099511628211ull;
  return h;
}

// ---- Encoding and decoding --------------------------------------------------------------------

// Writes a leaf's value in its encoding: `float64` kernels take the doubles as they are. An
// oversized offset puts three tiles' worth of the value in the offset (an FLWC not normalised).
void encode(const Leaf& leaf, const std::vector<double>& v, bool float64, bool oversized_offset, double* out) {
  auto put = [&](int i, double x) { out[leaf.offset + i] = float64 ? x : static_cast<double>(static_cast<float>(x)); };
  auto tiles = [&](double x) { return std::round(x / kTile) - (oversized_offset ? 3 : 0); };
  int n = leaf.components;
  switch (leaf.encoding) {
    case Encoding::plain:
      for (int i = 0; i < n; ++i) put(i, leaf.integer ? 0.0 : v[i]);  // indices and flags: 0
      break;
    case Encoding::df:
      for (int i = 0; i < n; ++i) {
        double hi = float64 ? v[i] : static_cast<float>(v[i]);
        put(i, hi), put(n + i, v[i] - hi);
      }
      break;
    case Encoding::lwc:
      for (int i = 0; i < n; ++i) {
        double tile = tiles(v[i]);
        put(i, tile), put(n + i, v[i] - tile * kTile);
      }
      break;
    case Encoding::df_matrix:
    case Encoding::lwc_matrix: {
      // The large part of the translation moves out of the float matrix.
      Vec big{};
      for (int r = 0; r < 3; ++r) {
        if (leaf.encoding == Encoding::lwc_matrix) big[r] = tiles(v[12 + r]) * kTile;
        else if (!float64) big[r] = static_cast<float>(v[12 + r]);
      }
      for (int i = 0; i < 16; ++i) put(i, i >= 12 && i < 15 ? v[i] - big[i - 12] : v[i]);
      for (int r = 0; r < 3; ++r) put(16 + r, leaf.encoding == Encoding::lwc_matrix ? big[r] / kTile : big[r]);
      break;
    }
    case Encoding::df_inverse_matrix:
    case Encoding::lwc_inverse_matrix: {
      // The object's large translation moves out of the float matrix: M = M' T(-origin), so
      // local = M' (P - origin). FDFInverseMatrix subtracts its PreTranslation (= origin) before M'
      // (UE 5.4's DoubleFloat.ush); FLWCInverseMatrix adds its Tile, which holds minus the tiles.
      std::array<double, 9> m3{};
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) m3[c * 3 + r] = v[c * 4 + r];
      Vec origin = neg(Vec{v[12], v[13], v[14]});
      Vec world_origin{};  // M^-1's translation is -R^-1 T: recover T = -R (translation part)
      std::array<double, 9> m3_inverse = inverse3(m3);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) world_origin[r] += m3_inverse[c * 3 + r] * origin[c];
      Vec moved{};  // the part of the object's origin taken out of M
      for (int r = 0; r < 3; ++r)
        moved[r] = leaf.encoding == Encoding::lwc_inverse_matrix ? tiles(world_origin[r]) * kTile
                   : float64                                     ? 0.0
                                                                 : static_cast<float>(world_origin[r]);
      // M T(moved): only the translation column (12..15) changes. Written out, so that an
      // infinite translation does not turn the rotation into NaN through 0 * inf.
      for (int i = 0; i < 12; ++i) put(i, v[i]);
      for (int r = 0; r < 4; ++r) {
        double column = v[12 + r];
        for (int k = 0; k < 3; ++k)
          if (v[k * 4 + r] != 0 && moved[k] != 0) column += v[k * 4 + r] * moved[k];
        put(12 + r, column);
      }
      for (int r = 0; r < 3; ++r) put(16 + r, leaf.encoding == Encoding::lwc_inverse_matrix ? -moved[r] / kTile : moved[r]);
      break;
    }
  }
}

// A leaf's value from a record, as its `components` doubles: what the shader sees of an input
// (High + Low, Tile * 2^21 + Offset, a matrix with its translation put back), or an output.
std::vector<double> decode(const Leaf& leaf, const double* in) {
  const double* at = in + leaf.offset;
  int n = leaf.components;
  std::vector<double> out;
  switch (leaf.encoding) {
    case Encoding::plain:
      out.assign(at, at + n);
      break;
    case Encoding::df:
      for (int i = 0; i < n; ++i) out.push_back(at[i] + at[n + i]);
      break;
    case Encoding::lwc:
      for (int i = 0; i < n; ++i) out.push_back(at[i] * kTile + at[n + i]);
      break;
    case Encoding::df_matrix:
    case Encoding::lwc_matrix:
      out.assign(at, at + 16);
      for (int r = 0; r < 3; ++r) out[12 + r] += leaf.encoding == Encoding::lwc_matrix ? at[16 + r] * kTile : at[16 + r];
      break;
    case Encoding::df_inverse_matrix:
    case Encoding::lwc_inverse_matrix: {
      Mat4 shifted{};
      std::copy(at, at + 16, shifted.begin());
      Vec moved{};
      for (int r = 0; r < 3; ++r) moved[r] = leaf.encoding == Encoding::lwc_inverse_matrix ? -at[16 + r] * kTile : at[16 + r];
      Mat4 m = multiply(shifted, translation(neg(moved)));
      out.assign(m.begin(), m.end());
      break;
    }
  }
  return out;
}

// Output leaves are matched across variants by path, with "Translated" dropped: a variant's
// `vTranslatedWorldPosition` is the original's `vWorldPosition`, in the translated frame.
std::string frame_free(const std::string& path, bool& translated) {
  std::string out = path;
  translated = false;
  for (const char* word : {"Translated", "translated"})
    for (size_t at; (at = out.find(word)) != std::string::npos;) out.erase(at, 10), translated = true;
  return out;
}

// A name that says its value is camera-relative (`TranslatedWorldPoint`).
bool in_translated_frame(const std::string& name) { return name.find("Translated") != std::string::npos || name.find("translated") != std::string::npos; }

bool is_clip(const Leaf& leaf) { return has(leaf.path, "gl_Position") || lower(leaf.semantic) == "sv_position"; }

float ulp32(double x) {
  float m = std::max(std::fabs(static_cast<float>(x)), 1.0f);
  return std::nextafter(m, std::numeric_limits<float>::infinity()) - m;
}

double distance(const State& s) {
  Vec d = sub(s.world(), s.camera);
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

struct Kernel {
  HarnessKernel code;
  CompileResult compiled;
  std::string problem;
};

// Whether code calls `name` (an identifier followed by an opening parenthesis).
bool calls(std::string_view code, std::string_view name) {
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t at = code.find(name); at != std::string_view::npos; at = code.find(name, at + 1)) {
    size_t after = at + name.size();
    while (after < code.size() && (code[after] == ' ' || code[after] == '\t')) ++after;
    if ((at == 0 || !ident(code[at - 1])) && after < code.size() && code[after] == '(') return true;
  }
  return false;
}

// The first library function with a fault (HarnessSetup::library_faults) a kernel calls, and why:
// "" when it calls none.
std::string faulty_call(const HarnessKernel& k, const std::map<std::string, std::string>& faults) {
  for (const auto& [name, why] : faults)
    if (calls(k.declarations, name) || calls(k.body, name))
      return fmt::format("`{}`, which fails the DoubleFloat library's own check on this driver ({}), so the library is at fault, "
                         "not this code", name, why);
  return "";
}

// ---- Error-free transformations ---------------------------------------------------------------

// A function lint found an error-free transformation in (FunctionFacts::error_free), called with
// its float operands and returning its (high, low) pair: the shape its defining property is judged
// on. Its float64 promotion is no reference: in double the transformation's low part is 0.
struct ErrorFreeCall {
  std::string operation;         // "sum", "fast-sum", "product", "split"
  std::vector<size_t> operands;  // input leaves, in parameter order
};

std::optional<ErrorFreeCall> error_free_call(const FunctionFacts& facts, const std::string& function, const HarnessKernel& k) {
  auto it = facts.error_free.find(function);
  if (it == facts.error_free.end()) return std::nullopt;
  ErrorFreeCall call{it->second, {}};
  for (size_t l = 0; l < k.inputs.size(); ++l) {
    const Leaf& leaf = k.inputs[l];
    if (leaf.path.starts_with("lwc_p") && leaf.components == 1 && !leaf.integer && leaf.encoding == Encoding::plain)
      call.operands.push_back(l);
  }
  int components = 0;
  for (const Leaf& o : k.outputs) components += o.integer ? 3 : o.components;  // a decision is not half of a pair
  if (call.operands.size() != (call.operation == "split" ? 1u : 2u) || components != 2) return std::nullopt;
  return call;
}

// The operands' failure modes (the library's adversarial cases): cancellation, exponent gaps and
// ties for sums, |a| >= |b| for Fast2Sum (its precondition), significands just above 1 and
// all-ones for products and splits.
InputFamily operand_family(const std::string& operation) {
  return operation == "sum" ? InputFamily::sum : operation == "fast-sum" ? InputFamily::ordered : InputFamily::product;
}

int significant_bits(float x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int exponent;
  auto m = static_cast<uint32_t>(std::frexp(std::fabs(x), &exponent) * 0x1p24);
  int bits = 24;
  for (; m % 2 == 0; m /= 2) --bits;
  return bits;
}

// The defining property on one input: high + low is exactly the sum, the product or the split
// value of the operands (a double-double on the CPU), and the pair is canonical: a sum's or a
// product's high part is that value rounded to float, a split's halves hold 12 bits each. "" when
// it holds, else what is wrong; `ulps` gets how far high + low is off, in ULPs of the exact value.
std::string error_free_miss(const std::string& operation, float a, float b, float high, float low, double& ulps) {
  dd::Value exact = operation == "split"     ? dd::from(a)
                    : operation == "product" ? dd::from(static_cast<double>(a) * b)  // 48 bits: exact in double
                                             : dd::two_sum(a, b);
  dd::Value got = dd::two_sum(high, low), off = dd::sub(got, exact);
  float rounded = std::fabs(static_cast<float>(exact.hi));
  ulps = std::fabs(off.approx()) / (std::nextafter(rounded, std::numeric_limits<float>::infinity()) - rounded);
  if (!std::isfinite(got.hi)) ulps = std::numeric_limits<double>::infinity();
  if (!(ulps == 0))
    return fmt::format("high + low = {:.17g} where the exact value is {:.17g} ({:.3g} ULPs off)", got.approx(), exact.approx(), ulps);
  if (operation == "split") {
    if (significant_bits(high) > 12 || significant_bits(low) > 12)
      return fmt::format("the halves {:.9g} and {:.9g} hold {} and {} significant bits, where a split's hold at most 12", high,
                         low, significant_bits(high), significant_bits(low));
    return "";
  }
  float neighbour = std::nextafter(high, low > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity());
  if (std::fabs(low) > std::fabs(static_cast<double>(neighbour) - high) / 2)
    return fmt::format("not canonical: the low part {:.9g} is more than half an ULP of the high part {:.9g}", low, high);
  return "";
}

// A variant's text, preprocessed (promoted to double for the reference), and whether the whole
// file compiles; once per file and variant, not per function.
struct PreparedVariant {
  PreprocessResult pre;
  std::string text;                           // preprocessed, promoted when float64
  std::optional<CompileResult> whole_failed;  // float32 only: the file's own compile error
};

// A unitless result (a colour, a direction, a fraction, a dot product) passes within 2^-12 of
// max(|reference|, 1): a sixteenth of an 8-bit colour step, 0.014 degrees of a unit direction. In
// float32 ULPs of max(|reference|, 1) that is 2^11; as a factor on ULPs, its inverse.
constexpr double kUlpsPerUnitlessTolerance = 0x1p-11;

// Costs closer than this (relative) are not told apart, whatever the spreads say: on a shared
// 2-core machine the same SPIR-V measured up to 12% apart between two idle runs, and two
// variants of equal size more than 15% apart under a loaded CI run (a pick flipped).
constexpr double kSameCost = 0.25;

// Whether `a` runs faster than `b` by more than the measurement can tell apart: by more than the
// larger of their spreads, and at least 25%. The same SPIR-V costs the same.
bool clearly_faster(const VariantResult& a, const VariantResult& b) {
  if (a.spirv_hash == b.spirv_hash && a.spirv_hash != 0) return false;
  double margin = std::max({kSameCost, a.cost_spread, b.cost_spread});
  return a.ns_per_invocation < b.ns_per_invocation * (1 - margin);
}

}  // namespace

class VariantCache {
 public:
  std::shared_ptr<const PreparedVariant> get(const std::string& key, const std::function<PreparedVariant()>& make) {
    {
      std::lock_guard lock(mutex_);
      if (auto it = prepared_.find(key); it != prepared_.end()) return it->second;
    }
    auto made = std::make_shared<const PreparedVariant>(make());  // outside the lock: another file's work may run meanwhile
    std::lock_guard lock(mutex_);
    return prepared_.emplace(key, std::move(made)).first->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const PreparedVariant>> prepared_;
};

std::shared_ptr<VariantCache> make_variant_cache() { return std::make_shared<VariantCache>(); }

void pick_variant(FunctionResult& result, double precision) {
  // The error/time Pareto front and the scene's pick (the fastest that meets the target), both
  // over the variants that pass and that fix can write: a failing or unwritable variant is no choice.
  // Costs the measurement cannot tell apart count as equal, so two runs give the same front and pick.
  auto choice = [](const VariantResult& v) { return v.passed() && v.writable; };
  // The error axis: world units where the function has a result in them, else float32 ULPs.
  auto error = [](const VariantResult& v) { return v.world_outputs ? v.max_error : v.max_ulps; };
  for (VariantResult& a : result.variants) {
    a.pareto = false;
    if (!choice(a)) continue;
    a.pareto = true;
    for (const VariantResult& b : result.variants)
      if (&a != &b && choice(b) && error(b) <= error(a) && !clearly_faster(a, b) && (error(b) < error(a) || clearly_faster(b, a)))
        a.pareto = false;
  }
  // The fastest; among those it cannot tell apart from the fastest, the one with the fewest SPIR-V
  // instructions, then the first.
  const VariantResult* fastest = nullptr;
  for (const VariantResult& v : result.variants)
    if (choice(v) && (!fastest || v.ns_per_invocation < fastest->ns_per_invocation)) fastest = &v;
  const VariantResult* pick = nullptr;
  int passing = 0, tied = 0;
  for (const VariantResult& v : result.variants) {
    passing += choice(v);
    if (!choice(v) || clearly_faster(*fastest, v)) continue;
    ++tied;
    if (!pick || v.spirv_instructions < pick->spirv_instructions) pick = &v;
  }
  if (!pick) {
    result.pick = fmt::format("none: no variant fix can write keeps the error within {}", format_distance(precision));
    return;
  }
  result.pick = fmt::format("{}: the fastest of the {} variant(s) within {} ({:.3g} ns per invocation", pick->label, passing,
                            format_distance(precision), pick->ns_per_invocation);
  if (tied > 1)
    result.pick += fmt::format("; {} run equally fast within the measurement's spread, and it has the fewest SPIR-V instructions ({})",
                               tied, pick->spirv_instructions);
  result.pick += ")";
}

std::vector<std::string> harness_case_names() {
  std::vector<std::string> out;
  for (const Case& c : cases()) out.push_back(c.name);
  return out;
}

FunctionResult verify_function(WorkerDevice& device, const DriverProbes& probes, const HarnessSetup& setup,
                               const std::string& function, const std::vector<FileVariant>& variants) {
  FunctionResult result;
  result.file = setup.display;
  result.function = function;
  std::string fused = probes.fuses_fma() ? "1" : "0";

  // Preprocesses a variant and builds its kernel (float32 as written, or promoted to float64).
  auto build_kernel = [&](const FileVariant& v, bool float64) {
    Kernel k;
    CompileInput in;
    in.lang = setup.lang;
    in.stage = setup.stage;
    in.name = setup.display;
    in.text = without_bom(v.text);
    in.include = setup.include;
    in.preamble = "#define LWC_DF_FUSED_FMA " + fused + "\n" + define_lines(setup.defines);
    if (setup.unreal) in.preamble += fmt::format("#define LWCPORT_UE_VERSION {}\n", v.ue_version) + unreal_environment_text(v.text, setup.unreal_library);
    if (setup.lang == Lang::hlsl) {
      // Every part of the preprocessed text marked with where it came from (verify/kernel_builder.h).
      in.preamble = "#line 1 \"lwcport environment\"\n" + in.preamble;
      in.text = with_forced_includes(setup.force_includes, setup.display, v.text);
    }
    auto prepare = [&](bool as_float64) {
      std::string key = fmt::format("{}{}\n{}", as_float64 ? 'd' : 'f', v.ue_version, v.text);
      return setup.cache->get(key, [&] {
        PreparedVariant p;
        p.pre = preprocess_shader(in);
        if (p.pre.text.empty()) return p;
        p.text = as_float64 ? promote_to_double(setup.lang, p.pre.text) : p.pre.text;
        // The variant must compile as a shader of its own before it is cut down (errors on its own
        // lines). A file that does not compile as a whole may still hold this function compiling on
        // its own (the error is in another function): the harness kernel, cut down to what the
        // function needs, decides; if it fails too, the file's own error is the reason. In a child
        // process: this is the user's code, and glslang's error recovery can crash on it.
        if (!as_float64) {
          CompileInput check = in;
          if (setup.lang == Lang::hlsl) {
            check.entry = "lwcport_compile_check";
            check.text += "\nvoid lwcport_compile_check() {}\n";
          }
          if (CompileResult whole = compile_shader_isolated(check); !whole.ok) p.whole_failed = std::move(whole);
        }
        return p;
      });
    };
    std::shared_ptr<const PreparedVariant> prepared = prepare(float64);
    // Where glslang crashed on the code as written, no kernel of it is compiled in this process.
    if (std::shared_ptr<const PreparedVariant> written = float64 ? prepare(false) : prepared;
        written->whole_failed && !written->whole_failed->crashed.empty()) {
      k.problem = "not verifiable: " + written->whole_failed->crashed + " compiling the file";
      return k;
    }
    if (prepared->pre.text.empty()) {
      CompileResult r;
      r.messages = prepared->pre.messages;
      k.problem = "does not preprocess: " + format_messages(r);
      return k;
    }
    const std::optional<CompileResult>& whole_failed = prepared->whole_failed;
    // Why a function of a file that does not compile as a whole cannot be built: the errors in what
    // the function needs (a float32 kernel's lines are the file's), else the file's own.
    auto file_problem = [&](const CompileResult* kernel = nullptr) {
      const CompileResult& errors = kernel && kernel_says_where(k.code, *kernel) ? *kernel : *whole_failed;
      for (const CompileMessage& m : errors.messages)
        if (auto hand = v.hand_fixes.find(m.line); m.source == setup.display && hand != v.hand_fixes.end())
          return fmt::format("incomplete: line {} is in code lwcport could not port (no automatic fix for {} there), and "
                             "the file does not compile until it is fixed by hand: {}", m.line, hand->second, format_messages(errors));
      return "does not compile: " + format_messages(errors);
    };
    const std::string& text = prepared->text;
    k.code = build_harness_kernel(setup.lang, text, function, float64);
    if (!k.code.problem.empty()) {
      k.problem = whole_failed ? file_problem() : "not verifiable: " + k.code.problem;
      return k;
    }
    KernelSpec spec;
    spec.lang = setup.lang;
    spec.name = setup.display;
    spec.declarations = k.code.declarations;
    spec.body = k.code.body;
    spec.in_stride = k.code.in_stride;
    spec.out_stride = k.code.out_stride;
    spec.float64 = float64;
    // Code for GLSL ES stays ES (no `precise` before 3.20, as on the target); compute needs 3.10.
    if (std::string_view es = glsl_es_version(v.text); es == "300" || es == "310" || es == "320") spec.glsl_version = es == "320" ? "320 es" : "310 es";
    k.compiled = compile_kernel(spec);
    if (!k.compiled.ok)
      k.problem = whole_failed ? file_problem(float64 ? nullptr : &k.compiled) : "the harness kernel does not compile: " + format_messages(k.compiled);
    else if (std::string fault = faulty_call(k.code, setup.library_faults); !fault.empty())
      k.problem = "not judged: it calls " + fault;
    else if (float64) k.problem = float32_in_reference(k.compiled.spirv, kernel_source(spec));
    return k;
  };
  auto build = [&](const FileVariant& v, bool float64) {
    auto start = std::chrono::steady_clock::now();
    Kernel k = build_kernel(v, float64);
    result.compile_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return k;
  };

  size_t n = static_cast<size_t>(setup.invocations + kKernelGroupSize - 1) / kKernelGroupSize * kKernelGroupSize;
  std::vector<State> states(n);
  for (size_t i = 0; i < n; ++i) states[i] = make_state(i);
  std::vector<bool> drawn_at(n);
  for (size_t i = 0; i < n; ++i) drawn_at[i] = states[i].non_finite || distance(states[i]) <= setup.scene.view_distance;
  auto drawn = [&](size_t i) { return drawn_at[i]; };
  // An error-free transformation's operands (when lint found one in this function), from its
  // failure modes: the same values in float32 and in float64.
  std::vector<FloatOperands> operands;
  if (auto it = setup.facts.error_free.find(function); it != setup.facts.error_free.end())
    operands = float_operands(operand_family(it->second), n, !probes.keeps_denormals());

  // An input's role (role_for), and `source` what decided it.
  auto input_role = [&](const Leaf& leaf, std::string* source = nullptr) {
    auto [base, half] = split_half(leaf.name, leaf.encoding);
    std::optional<Kind> kind = model_kind(setup.facts, function, leaf);
    Role role = role_for(base, leaf.components, kind);
    bool bare_half = half != Half::none && base.empty();
    if (bare_half) role = Role::world_position;  // a bare `high`/`low` pair
    // A member of a light's struct or uniform buffer (`DeferredLightUniforms.Position`, the
    // `Position` of an FDeferredLightData parameter): the light's position, the second point of
    // light code, not the object's.
    bool of_light = has(lower(leaf.path + " " + leaf.owner), "light");
    bool named_position = has(lower(leaf.name), "pos");
    if (of_light && (role == Role::world_position || role == Role::translated_position || (role == Role::local_position && named_position)))
      role = role == Role::translated_position || has(lower(leaf.name), "translated") ? Role::translated_light : Role::light;
    if (source)
      *source = bare_half ? "by its name (a bare high/low half)"
                : kind && *kind != Kind::unknown ? fmt::format("by the world-space model (kind {})", kind_name(*kind))
                                                 : "by its name";
    return role;
  };

  // Fills the input records of a kernel from the states. Leaves marked in `as_float32` get what a
  // float32 kernel of the same type would see (the reference on a variant's inherited inputs), and
  // `rounding` gets, per leaf, the most that made a drawn value move.
  auto inputs_for = [&](const HarnessKernel& k, int ue_version, bool float64, const std::vector<bool>& as_float32 = {},
                        std::vector<double>* rounding = nullptr) {
    std::vector<double> record(k.in_stride), scratch(k.in_stride);
    // The records, written in place: a float64 kernel reads doubles, a float32 one floats.
    size_t width = float64 ? sizeof(double) : sizeof(float);
    std::vector<uint8_t> bytes(n * static_cast<size_t>(k.in_stride) * width);
    struct LeafRole {
      Role role;
      uint64_t hash;
      Half half;
    };
    std::vector<LeafRole> roles;  // per leaf, once: names are slow to read
    for (const Leaf& leaf : k.inputs) {
      Role role = input_role(leaf);
      if (std::optional<Role> in_place = in_place_role(leaf.name.substr(0, leaf.name.find('[')), ue_version)) role = *in_place;
      roles.push_back({role, fnv1a(leaf.name), split_half(leaf.name, leaf.encoding).second});
    }
    if (rounding) rounding->assign(k.inputs.size(), 0.0);
    std::vector<int> operand_of(k.inputs.size(), -1);
    if (std::optional<ErrorFreeCall> call = operands.empty() ? std::nullopt : error_free_call(setup.facts, function, k))
      for (size_t j = 0; j < call->operands.size(); ++j) operand_of[call->operands[j]] = static_cast<int>(j);
    for (size_t i = 0; i < n; ++i) {
      std::fill(record.begin(), record.end(), 0.0);
      for (size_t l = 0; l < k.inputs.size(); ++l) {
        const Leaf& leaf = k.inputs[l];
        std::vector<double> value = operand_of[l] >= 0 ? std::vector<double>{operand_of[l] == 0 ? operands[i].a : operands[i].b}
                                                       : role_value(roles[l].role, leaf.components, states[i], roles[l].hash, i);
        if (roles[l].half != Half::none)
          for (double& x : value) x = roles[l].half == Half::high ? static_cast<float>(x) : x - static_cast<float>(x);
        if (l < as_float32.size() && as_float32[l]) {
          encode(leaf, value, false, states[i].oversized_offset, scratch.data());
          std::vector<double> seen = decode(leaf, scratch.data());
          if (rounding && drawn(i))
            for (size_t c = 0; c < seen.size(); ++c)
              if (std::isfinite(value[c])) (*rounding)[l] = std::max((*rounding)[l], std::fabs(seen[c] - value[c]));
          value = std::move(seen);
        }
        encode(leaf, value, float64, states[i].oversized_offset, record.data());
      }
      uint8_t* at = bytes.data() + i * record.size() * width;
      if (float64) std::memcpy(at, record.data(), record.size() * width);
      else
        for (size_t c = 0; c < record.size(); ++c) {
          float x = static_cast<float>(record[c]);
          std::memcpy(at + c * width, &x, width);
        }
    }
    return bytes;
  };
  struct Run {
    std::vector<double> out;  // n * out_stride
    double seconds = 0;       // pipeline creation and the one dispatch (lavapipe compiles the shader in it)
    std::string problem;
  };
  uint32_t groups = static_cast<uint32_t>(n / kKernelGroupSize);
  auto run = [&](const Kernel& k, bool float64, std::vector<uint8_t> inputs, uint64_t* kept = nullptr) {
    Run r;
    std::vector<std::vector<uint8_t>> buffers = {std::move(inputs), std::vector<uint8_t>(n * k.code.out_stride * (float64 ? 8 : 4))};
    DispatchTiming timing;
    r.problem = device.run(k.compiled.spirv, buffers, groups, 1, &timing, kept, {false, true});
    if (!r.problem.empty()) return r;
    r.seconds = timing.pipeline_seconds + (timing.dispatch_seconds.empty() ? 0 : timing.dispatch_seconds.front());
    result.pipeline_seconds += r.seconds;
    if (float64) r.out = from_bytes<double>(buffers[1]);
    else for (float x : from_bytes<float>(buffers[1])) r.out.push_back(x);
    return r;
  };

  // Each input of a kernel, its role and how it is filled (verify --explain).
  // Each path once over the variants (`explained`); `whose` says which variant reads it first.
  std::set<std::string> explained;
  auto explain_inputs = [&](const HarnessKernel& k, const std::optional<ErrorFreeCall>& call, const std::string& whose = "") {
    std::vector<std::string> lines;
    for (size_t l = 0; l < k.inputs.size(); ++l) {
      const Leaf& leaf = k.inputs[l];
      if (!explained.insert(leaf.path).second) continue;
      std::string name = fmt::format("`{}` ({})", leaf.path, leaf.type);
      if (leaf.path.starts_with("lwc_texel_")) {
        name = fmt::format("a texel of `{}` ({})", leaf.path.substr(10), leaf.type);
      } else if (leaf.path.starts_with("lwc_p")) {
        size_t member = leaf.path.find_first_of(".[");
        int index = std::atoi(leaf.path.c_str() + 5) + 1;
        name = member == std::string::npos ? fmt::format("`{}` (parameter {}, {})", leaf.name, index, leaf.type)
                                           : fmt::format("`{}` of parameter {} ({})", leaf.path.substr(member), index, leaf.type);
      }
      std::string source;
      std::string what(role_text(input_role(leaf, &source)));
      if (leaf.integer) what = "0 (an index or a flag)", source = "by its type";
      if (call)
        for (size_t j = 0; j < call->operands.size(); ++j)
          if (call->operands[j] == l)
            what = fmt::format("operand {} of the error-free {}: the library's adversarial cases for it, then random floats", j + 1,
                               call->operation),
            source = "by lint's error-free transformation";
      auto [base, half] = split_half(leaf.name, leaf.encoding);
      std::string_view form = leaf.encoding == Encoding::df                    ? ", as a DoubleFloat pair"
                              : leaf.encoding == Encoding::lwc                 ? ", as a tile/offset pair"
                              : leaf.encoding == Encoding::df_matrix           ? ", as an FDFMatrix (PostTranslation after M)"
                              : leaf.encoding == Encoding::df_inverse_matrix   ? ", as an FDFInverseMatrix (PreTranslation before M)"
                              : leaf.encoding == Encoding::lwc_matrix          ? ", as an FLWCMatrix"
                              : leaf.encoding == Encoding::lwc_inverse_matrix  ? ", as an FLWCInverseMatrix"
                              : half == Half::high                             ? ", its high half (float)"
                              : half == Half::low                              ? ", its low half (the rest)"
                                                                               : "";
      lines.push_back(fmt::format("{}: {}{}; {}{}", name, what, form, source, whose));
    }
    return lines;
  };

  // The reference: the original, every float promoted to double.
  Kernel reference = build(variants.front(), true);
  std::optional<ErrorFreeCall> error_free = reference.problem.empty() ? error_free_call(setup.facts, function, reference.code) : std::nullopt;
  Run ref_run;
  if (reference.problem.empty() && !error_free) ref_run = run(reference, true, inputs_for(reference.code, variants.front().ue_version, true));
  if (error_free) {
    result.reference = fmt::format("exact: high + low against the operands' exact {} (a double-double on the CPU), the pair canonical",
                                   error_free->operation == "split" ? "value" : error_free->operation == "product" ? "product" : "sum");
  } else if (reference.problem.starts_with("not judged: it calls ")) {
    result.reference = "no reference to trust: the original calls " + reference.problem.substr(21);
  } else if (!reference.problem.empty() && !build(variants.front(), false).problem.empty()) {
    result.reference = "no float64 reference: the original does not compile (its error, with the file's lines, is below)";
  } else if (!reference.problem.empty() || !ref_run.problem.empty()) {
    result.reference = "no float64 reference: " + (reference.problem.empty() ? ref_run.problem : reference.problem);
  } else {
    result.reference = "the original promoted to float64 (transcendentals in float32)";
  }
  const std::vector<Leaf>& ref_inputs = reference.code.inputs;

  // The second reference, per set of inherited inputs: the reference run on what a variant sees of
  // the inputs it keeps from the original (same name and type), so the error it shows is the
  // variant's own arithmetic, not the rounding of values its callers hand it (LWC-BRIEF §6).
  struct Oracle {
    Run run;
    std::vector<double> rounding;  // per reference input
  };
  std::map<std::vector<bool>, Oracle> oracles;
  auto oracle_for = [&](const HarnessKernel& k) -> const Oracle* {
    std::map<std::string, const Leaf*> by_path;
    for (const Leaf& v : k.inputs) by_path[v.path] = &v;
    std::vector<bool> inherited(ref_inputs.size(), false);
    for (size_t l = 0; l < ref_inputs.size(); ++l)
      if (auto v = by_path.find(ref_inputs[l].path); v != by_path.end())
        inherited[l] = v->second->name == ref_inputs[l].name && promote_to_double(setup.lang, v->second->type) == ref_inputs[l].type;
    auto it = oracles.find(inherited);
    if (it == oracles.end()) {
      Oracle o;
      o.run = run(reference, true, inputs_for(reference.code, variants.front().ue_version, true, inherited, &o.rounding));
      it = oracles.emplace(inherited, std::move(o)).first;
    }
    return it->second.run.problem.empty() ? &it->second : nullptr;
  };

  std::map<std::string, const Leaf*> ref_outputs;
  for (const Leaf& l : reference.code.outputs) {
    bool translated;
    ref_outputs[frame_free(l.path, translated)] = &l;
  }

  // One output value against the reference: its error, in world units or float32 ULPs, and whether
  // it misses the target. `integer`: a decision (bool, index) must match exactly. In a non-finite
  // case, the result must be non-finite where the reference is, and finite where it is not.
  struct Verdict {
    double error = 0, ulps = 0;
    bool bad = false, off_screen = false;
    std::string what;  // set for a wrong decision or finiteness
    double score = 0;  // error over the target (world units, else the unitless tolerance); max when `what` is set
  };
  auto judge = [&](const std::vector<double>& got, const std::vector<double>& want, const State& s, bool integer, bool clip,
                   bool world) {
    Verdict v;
    if (integer) {
      for (size_t c = 0; c < got.size(); ++c) v.bad = v.bad || got[c] != want[c];
      if (v.bad) v.what = "a different decision";
    } else if (s.non_finite) {
      // A value is non-finite when any component is: normalize((-Inf, 0, 0)) is (NaN, 0, 0) in one
      // form and all NaN in another, and both keep the bad input visible.
      auto finite = [](const std::vector<double>& x) { return std::all_of(x.begin(), x.end(), [](double c) { return std::isfinite(c); }); };
      v.bad = finite(got) != finite(want);
      if (v.bad) v.what = "finite where the reference is not, or the reverse";
    } else if (clip && got.size() == 4) {
      // NDC error times the view depth (clip w): the world-space offset it shows as.
      double w = want[3];
      v.off_screen = !(w > 0) || std::fabs(want[0]) > w || std::fabs(want[1]) > w;  // not drawn
      for (int c = 0; c < 2; ++c) v.error = std::max(v.error, std::fabs(got[c] / got[3] - want[c] / w) * std::fabs(w));
      if (!std::isfinite(v.error)) v.error = std::numeric_limits<double>::infinity();
      v.bad = !(v.error <= setup.scene.precision);
    } else {
      for (size_t c = 0; c < got.size(); ++c) {
        double e = std::fabs(got[c] - want[c]);
        if (!std::isfinite(got[c]) && std::isfinite(want[c])) e = std::numeric_limits<double>::infinity();
        v.error = std::max(v.error, e);
        v.ulps = std::max(v.ulps, e / ulp32(want[c]));
      }
      v.bad = (world || clip) ? !(v.error <= setup.scene.precision) : !(v.ulps * kUlpsPerUnitlessTolerance <= 1);
    }
    v.score = !v.what.empty() ? std::numeric_limits<double>::max()
              : (world || clip)  ? v.error / setup.scene.precision
                                 : v.ulps * kUlpsPerUnitlessTolerance;
    if (!std::isfinite(v.score)) v.score = std::numeric_limits<double>::max();
    return v;
  };

  // The original as run, for the edge cases (+-0, denormals, Inf, NaN): there a variant fails only
  // where it does worse than the original did, since those cases test that a port keeps what the
  // original handled, not float32 itself (a denormal-length vector normalises to NaN in either).
  Kernel original_k;
  Run original_r;
  const Kernel* original_kernel = nullptr;
  const Run* original_run = nullptr;

  // A variant's outputs against a reference run, in the reference's frame.
  struct Comparison {
    std::vector<double> errors;  // world units (positions, offsets, clip as a world offset)
    double max_ulps = 0;
    int mismatches = 0;          // integer and bool results that differ
    bool failed = false;
    double worst_score = -1;
    std::string worst;
    std::string unmatched;
    // Per case (harness_case_names), outside the edge cases: the worst score, its error in the
    // output's own terms, and how far the object was from the camera there; -1 where none was judged.
    std::vector<double> case_score = std::vector<double>(cases().size(), -1), case_error = case_score, case_distance = case_score;
    // Per case, the largest component of the worst world-unit output as the variant holds it (its
    // own frame): an absolute position cannot be closer than half its own float32 spacing.
    std::vector<double> case_magnitude = std::vector<double>(cases().size(), -1);
    bool world = false;  // some judged output is in world units (the case errors are cm)
  };
  std::optional<Comparison> original_total;  // the original against the reference, per case
  auto compare = [&](const Kernel& k, const Run& r, const Run& ref, bool is_original) {
    Comparison cmp;
    for (const Leaf& leaf : k.code.outputs) {
      bool translated;
      std::string key = frame_free(leaf.path, translated);
      translated = translated || in_translated_frame(leaf.name);  // an `out` parameter renamed so (`lwc_p1`)
      auto match = ref_outputs.find(key);
      if (match == ref_outputs.end()) {
        cmp.unmatched += (cmp.unmatched.empty() ? "" : ", ") + leaf.path;
        continue;
      }
      const Leaf& ref_leaf = *match->second;
      bool ref_translated;
      frame_free(ref_leaf.path, ref_translated);
      ref_translated = ref_translated || in_translated_frame(ref_leaf.name);
      // What the result is: the model's kind of the function's return, of a global or an `out`
      // parameter, or of its path in the world-space data; else its name.
      Role role = ref_leaf.name == "return" ? role_of(function, ref_leaf.components)
                                            : role_for(ref_leaf.name, ref_leaf.components, model_kind(setup.facts, function, ref_leaf));
      if (auto kind = setup.facts.returns.find(function); ref_leaf.name == "return" && kind != setup.facts.returns.end())
        role = role_of_kind(kind->second).value_or(role);
      if (lower(ref_leaf.semantic).starts_with("sv_target")) role = Role::other;  // a render target's value: unitless
      bool clip = is_clip(ref_leaf);
      bool world = !clip && (world_units(role) || translated != ref_translated);
      bool integer = ref_leaf.integer || leaf.integer;
      const Leaf* original_leaf = nullptr;
      if (original_kernel)
        for (const Leaf& o : original_kernel->code.outputs) {
          bool unused;
          if (frame_free(o.path, unused) == key && o.components == leaf.components) original_leaf = &o;
        }
      for (size_t i = 0; i < n; ++i) {
        const State& s = states[i];
        if (!drawn(i)) continue;  // not drawn in this scene
        std::vector<double> got = decode(leaf, &r.out[i * k.code.out_stride]);
        std::vector<double> want = decode(ref_leaf, &ref.out[i * reference.code.out_stride]);
        if (got.size() != want.size()) continue;
        double magnitude = 0;  // in the variant's own frame, before any move
        for (int c = 0; c < 3 && c < static_cast<int>(got.size()); ++c) magnitude = std::max(magnitude, std::abs(got[c]));
        if (translated != ref_translated)  // move the variant's value into the reference's frame
          for (int c = 0; c < 3 && c < static_cast<int>(got.size()); ++c) got[c] += (translated ? 1 : -1) * s.camera[c];
        Verdict v = judge(got, want, s, integer, clip, world);
        if (v.off_screen) continue;
        if (s.edge) {
          if (!v.bad || is_original) continue;  // edge cases say nothing about precision; the original is their baseline
          if (original_leaf) {
            std::vector<double> before = decode(*original_leaf, &original_run->out[i * original_kernel->code.out_stride]);
            Verdict o = judge(before, want, s, integer, clip, world);
            if (o.bad && o.score >= v.score) continue;  // no worse than the original
          }
        }
        cmp.failed |= v.bad;
        if (integer) cmp.mismatches += v.bad;
        if (size_t c = i % cases().size(); !s.edge && v.what.empty() && v.score > cmp.case_score[c]) {
          cmp.case_score[c] = v.score, cmp.case_error[c] = v.error, cmp.case_distance[c] = distance(s);
          cmp.case_magnitude[c] = world && !clip ? magnitude : -1;
          cmp.world |= world || clip;
        }
        if ((world || clip) && !s.non_finite && !integer) cmp.errors.push_back(v.error);
        cmp.max_ulps = std::max(cmp.max_ulps, v.ulps);
        if (v.score > cmp.worst_score) {
          cmp.worst_score = v.score;
          std::string amount = !v.what.empty()    ? v.what
                               : (world || clip) ? fmt::format("error {:.3g} cm", v.error)
                                                 : fmt::format("error {:.3g} ({:.3g} ULPs)", v.error, v.ulps);
          cmp.worst = fmt::format("case '{}': camera ({:.17g}, {:.17g}, {:.17g}), object origin ({:.17g}, {:.17g}, {:.17g}); "
                                  "`{}` expected ({:.9g}), got ({:.9g}); {}",
                                  cases()[i % cases().size()].name, s.camera[0], s.camera[1], s.camera[2], s.origin[0], s.origin[1],
                                  s.origin[2], ref_leaf.path == "lwc_result" ? "return value" : ref_leaf.path, fmt::join(want, ", "),
                                  fmt::join(got, ", "), amount);
        }
      }
    }
    return cmp;
  };

  // An error-free transformation's (high, low) result against the exact value of its operands.
  auto judge_error_free = [&](const Kernel& k, const Run& r, VariantResult& vr) {
    std::optional<ErrorFreeCall> call = error_free_call(setup.facts, function, k.code);
    if (!call) {
      vr.status = "not compared: this form no longer takes the transformation's float operands and returns its (high, low) pair";
      return;
    }
    std::vector<std::string> case_names = adversarial_case_names(operand_family(call->operation));
    size_t misses = 0;
    double worst_ulps = -1;
    std::vector<double> pair;
    for (size_t i = 0; i < n; ++i) {
      pair.clear();
      for (const Leaf& o : k.code.outputs)
        for (double x : decode(o, &r.out[i * k.code.out_stride])) pair.push_back(x);
      const FloatOperands& in = operands[i];
      double ulps = 0;
      std::string miss = error_free_miss(call->operation, in.a, in.b, static_cast<float>(pair[0]), static_cast<float>(pair[1]), ulps);
      vr.max_ulps = std::max(vr.max_ulps, ulps);
      if (miss.empty()) continue;
      ++misses;
      if (ulps <= worst_ulps) continue;
      worst_ulps = ulps;
      vr.worst = fmt::format("case '{}': operands {:.9g}{}; {}", in.case_index < 0 ? "random" : case_names[in.case_index], in.a,
                             call->operation == "split" ? "" : fmt::format(", {:.9g}", in.b), miss);
    }
    vr.own_max_ulps = vr.max_ulps;
    vr.status = misses ? "fail" : "pass";
    if (misses) {
      vr.worst += fmt::format(" ({} of {} inputs miss)", misses, n);
      vr.worst_over_target = std::isfinite(vr.max_ulps) ? std::max(vr.max_ulps, 1.0) : std::numeric_limits<double>::max();
    }
  };

  // Where a failing variant misses: each case over the target with the original's error on it, and
  // how many cases it meets. A rewrite limited by float32 work it keeps (the product with an
  // ill-conditioned object matrix; a far object in float32 translated world) shows it here.
  auto where_it_misses = [&](const Comparison& own, const Comparison& original) {
    std::vector<std::string> missed;
    int met = 0;
    auto amount = [](const Comparison& c, size_t k) {
      return c.world ? fmt::format("{:.3g} cm", c.case_error[k]) : fmt::format("{:.3g}", c.case_error[k]);
    };
    for (size_t c = 0; c < cases().size(); ++c) {
      if (own.case_score[c] < 0) continue;
      if (own.case_score[c] <= 1) {
        ++met;
        continue;
      }
      std::string text = fmt::format("'{}' ({}", cases()[c].name, amount(own, c));
      if (own.world && own.case_distance[c] > 0) {
        // What a float32 translated position can hold there: its spacing at that distance.
        int exponent;
        std::frexp(own.case_distance[c], &exponent);
        text += fmt::format(", the object {:.3g} cm from the camera, where float32 values are {:.3g} cm apart", own.case_distance[c],
                            std::ldexp(1.0, exponent - 24));
        // A result held as a large float32 (an absolute position) has the spacing of its own
        // magnitude, whatever the variant computed it from: say so where it is the wider one.
        if (own.case_magnitude[c] > own.case_distance[c] && own.case_magnitude[c] < INFINITY) {
          int result_exponent;
          std::frexp(own.case_magnitude[c], &result_exponent);
          if (result_exponent > exponent)
            text += fmt::format("; the result itself is {:.3g} cm from the origin in float32, where values are {:.3g} cm apart",
                                own.case_magnitude[c], std::ldexp(1.0, result_exponent - 24));
        }
      }
      missed.push_back(text + (original.case_score[c] >= 0 ? fmt::format("; the original {})", amount(original, c)) : ")"));
    }
    if (missed.empty()) return std::string();
    return fmt::format("; it misses the target on {} of {} cases: {}; within it on the other {}", missed.size(), missed.size() + met,
                       fmt::join(missed, ", "), met);
  };

  // The variants that ran, timed together once their results are known (result index, the
  // kernel kept in the driver process).
  std::vector<std::pair<size_t, uint64_t>> timed;
  std::map<int, Kernel> original_at_era;  // the original built for a variant's engine era
  for (const FileVariant& v : variants) {
    VariantResult vr;
    vr.label = v.label;
    vr.writable = v.writable;
    Kernel k = build(v, false);
    // The first variant's inputs, then any a rewrite reads that the original does not (a uniform
    // the host must set beside an absolute one).
    std::vector<std::string> lines =
        &v == &variants.front() ? explain_inputs(k.code, error_free) : explain_inputs(k.code, std::nullopt, fmt::format(" (read by the {} variant, not the original)", v.label));
    result.inputs.insert(result.inputs.end(), lines.begin(), lines.end());
    if (!k.problem.empty()) {
      vr.status = k.problem;
      result.variants.push_back(vr);
      continue;
    }
    // A rewrite that leaves this function and everything it uses as they were is not a rewrite
    // of it: neither passed nor refuted, whatever the original does.
    // (Against the original built for this variant's engine era: a fixed Unreal file compiles
    // against UE 5.4, and a function the fix left alone still reads 5.4's types there.)
    auto same_as_original = [&] {
      if (!original_kernel) return false;
      const Kernel* original = original_kernel;
      if (v.ue_version != variants.front().ue_version) {
        auto [at, added] = original_at_era.try_emplace(v.ue_version);
        if (added) {
          FileVariant at_era = variants.front();
          at_era.ue_version = v.ue_version;
          at->second = build(at_era, false);
        }
        if (!at->second.problem.empty()) return false;
        original = &at->second;
      }
      return same_code(k.code.declarations, original->code.declarations) && k.code.body == original->code.body;
    };
    if (same_as_original()) {
      vr.status = "unchanged: the fix leaves this function and everything it uses as in the original";
      result.variants.push_back(vr);
      continue;
    }
    SpirvSummary spirv = inspect_spirv(k.compiled.spirv);
    vr.spirv_instructions = spirv.instructions;
    vr.spirv_hash = fnv1a(k.compiled.spirv);
    vr.contraction_losses = contraction_losses(spirv);
    uint64_t kept = 0;
    Run r = run(k, false, inputs_for(k.code, v.ue_version, false), &kept);
    if (!r.problem.empty()) {
      vr.status = "did not run: " + r.problem;
      result.variants.push_back(vr);
      continue;
    }
    vr.pipeline_seconds = r.seconds;
    vr.measured = true;
    timed.emplace_back(result.variants.size(), kept);
    bool is_original = &v == &variants.front();
    Comparison total;
    if (error_free) {
      judge_error_free(k, r, vr);
    } else {
      const Oracle* oracle = ref_run.problem.empty() && reference.problem.empty() ? oracle_for(k.code) : nullptr;
      if (!oracle) {
        vr.status = "timed only: " + result.reference;
        result.variants.push_back(vr);
        continue;
      }
      total = compare(k, r, ref_run, is_original);
      Comparison own = compare(k, r, oracle->run, is_original);
      vr.world_outputs = !total.errors.empty();
      if (!total.errors.empty()) {
        vr.max_error = *std::max_element(total.errors.begin(), total.errors.end());
        std::nth_element(total.errors.begin(), total.errors.begin() + total.errors.size() / 2, total.errors.end());
        vr.median_error = total.errors[total.errors.size() / 2];
      }
      if (!own.errors.empty()) vr.own_max_error = *std::max_element(own.errors.begin(), own.errors.end());
      vr.max_ulps = total.max_ulps;
      vr.own_max_ulps = own.max_ulps;
      vr.mismatches = total.mismatches;
      vr.worst_over_target = std::max(total.worst_score, 0.0);
      if (own.failed) {
        vr.status = "fail";
        vr.worst = own.worst;
        if (!is_original && original_total) vr.worst += where_it_misses(own, *original_total);
      } else if (total.failed) {
        vr.status = "input-limited";
        std::vector<std::pair<double, std::string>> rounded;
        for (size_t l = 0; l < ref_inputs.size(); ++l) {
          Role role = input_role(ref_inputs[l]);
          if (oracle->rounding[l] > 0 && (world_units(role) || ref_inputs[l].components >= 9))
            rounded.emplace_back(oracle->rounding[l], ref_inputs[l].name);
        }
        std::sort(rounded.rbegin(), rounded.rend());
        for (size_t i = 0; i < rounded.size() && i < 3; ++i)
          vr.inherited_rounding += fmt::format("{}`{}` by up to {:.3g} cm", i ? ", " : "", rounded[i].second, rounded[i].first);
        vr.worst = total.worst + "; its own arithmetic is within the target on the inputs as it receives them" +
                   (vr.inherited_rounding.empty() ? "" : "; inherited inputs round: " + vr.inherited_rounding);
      } else {
        vr.status = "pass";
      }
    }
    if (!vr.contraction_losses.empty()) vr.status = "fail: lost NoContraction";
    // A rewrite that keeps, inside this very function, code lwcport could not port (a finding with
    // no automatic fix: a kept `LWCHackToFloat`, say) is incomplete there, not refuted.
    if (vr.status == "fail" && &v != &variants.front() && !v.hand_fixes.empty()) {
      Source text(setup.display, v.text);
      std::vector<uint32_t> starts;
      std::vector<int> lines;
      for (const auto& [line, rules] : v.hand_fixes)
        if (line >= 1 && line <= text.line_count()) starts.push_back(text.offset({line, 1})), lines.push_back(line);
      std::vector<std::string> in = enclosing_functions(setup.lang, v.text, starts);
      for (size_t i = 0; i < in.size(); ++i)
        if (in[i] == function) {
          vr.status = fmt::format("incomplete: line {} is in code lwcport could not port (no automatic fix for {} there); "
                                  "the error is what that code keeps", lines[i], v.hand_fixes.at(lines[i]));
          break;
        }
    }
    if (!total.unmatched.empty())
      vr.worst += (vr.worst.empty() ? "" : "; ") + std::string("not compared (no counterpart in the original): ") + total.unmatched;
    result.variants.push_back(vr);
    if (is_original) {
      original_k = std::move(k), original_r = std::move(r), original_total = std::move(total);
      original_kernel = &original_k, original_run = &original_r;
    }
  }

  // Run time: every variant that ran, timed in interleaved rounds on the same inputs, so a change
  // in the machine's load falls on all of them alike (docs/verify.md, "Costs").
  if (!timed.empty()) {
    std::vector<uint64_t> kernels;
    for (auto [index, kept] : timed) kernels.push_back(kept);
    InterleavedTiming t;
    if (std::string problem = device.time_interleaved(kernels, setup.timing, t); !problem.empty()) {
      result.timing = "not timed: " + problem;
    } else {
      result.timing_rounds = t.rounds;
      for (size_t i = 0; i < timed.size(); ++i) {
        VariantResult& vr = result.variants[timed[i].first];
        vr.ns_per_invocation = median_of(t.seconds[i]) / static_cast<double>(n) * 1e9;
        vr.cost_spread = median_spread(t.seconds[i]);
        for (double s : t.seconds[i]) result.dispatch_seconds += s * t.dispatches_per_sample[i];
      }
    }
  }
  pick_variant(result, setup.scene.precision);
  return result;
}

}  // namespace lwc
