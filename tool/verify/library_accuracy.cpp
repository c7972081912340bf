#include "verify/library_accuracy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <set>

#include "shaderlib/shaderlib.h"
#include "verify/kernel.h"
#include "verify/spirv.h"
#include "verify/worker.h"

namespace lwc {

namespace {

constexpr double kU = 5.9604644775390625e-08;  // 2^-24, float32's unit roundoff
constexpr double kU2 = kU * kU;
constexpr double kTile = 0x1p21;  // UE 5.0-5.3's tile size, as the engine defines it

using dd::Value;

// ---- Inputs -------------------------------------------------------------------------------

struct Pair {
  float hi = 0, lo = 0;
  Value value() const { return dd::from(hi, lo); }
};

struct Operands {
  Pair a, b;
  int case_id = 0;  // 0: random; else 1 + index into the family's adversarial cases
};

float ulp_of(float x) {
  float m = std::fabs(x);
  return std::nextafter(m, std::numeric_limits<float>::infinity()) - m;
}

// The canonical pair nearest a double-double value: High + Low == High in float32.
Pair to_pair(Value v) {
  float hi = static_cast<float>(v.hi);
  float lo = static_cast<float>((v.hi - static_cast<double>(hi)) + v.lo);
  float s = hi + lo;
  return {s, lo - (s - hi)};
}

class Random {
 public:
  explicit Random(uint64_t seed) : g_(seed) {}
  double uniform() { return std::uniform_real_distribution<double>(0.0, 1.0)(g_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g_); }
  bool coin() { return integer(0, 1) == 1; }
  float sign() { return coin() ? 1.0f : -1.0f; }
  // A float with a random 24-bit significand and an exponent in [emin, emax].
  float magnitude(int emin, int emax) { return std::ldexp(static_cast<float>(1.0 + integer(0, (1 << 23) - 1) * 0x1p-23), integer(emin, emax)); }
  // A canonical pair with a random low part of random size below half an ULP of the high.
  Pair pair(int emin, int emax) {
    float hi = sign() * magnitude(emin, emax);
    double lo = (uniform() - 0.5) * ulp_of(hi) * std::ldexp(1.0, -integer(0, 8));
    return to_pair(dd::from(hi, lo));
  }
  Pair scaled(Value v, double factor) { return to_pair(dd::mul(v, dd::from(factor))); }

 private:
  std::mt19937_64 g_;
};

using CaseMaker = std::function<Operands(Random&)>;
struct NamedCase {
  std::string name;
  CaseMaker make;
  // Outside the library's domain on some drivers (see measure).
  enum class Domain { inside, beyond_split_limit, denormal_range } domain = Domain::inside;
};

// B relative to A by a factor (1 + t): t small makes them cancel (negative factor) or close.
Pair near(Random& r, const Pair& a, int min_bits, int max_bits, float sign) {
  double t = r.sign() * std::ldexp(r.uniform() + 0.5, -r.integer(min_bits, max_bits));
  return r.scaled(a.value(), sign * (1.0 + t));
}

std::vector<NamedCase> adversarial_cases(InputFamily family) {
  using F = InputFamily;
  bool sums = family == F::sum || family == F::same_sign || family == F::opposite || family == F::ordered;
  std::vector<NamedCase> cases;
  auto add = [&](bool when, std::string name, CaseMaker make) {
    if (when) cases.push_back({std::move(name), std::move(make)});
  };
  add(family != F::quotient && family != F::close && family != F::opposite, "zero operand",
      [](Random& r) { return Operands{r.pair(-40, 40), {}}; });
  add(family == F::quotient, "zero dividend", [](Random& r) { return Operands{{}, r.pair(-40, 40)}; });
  add(family == F::sum || family == F::same_sign, "signed zeros",
      [](Random& r) { return Operands{{-0.0f, r.coin() ? 0.0f : -0.0f}, {0.0f, -0.0f}}; });
  add(true, "low at a tie (|Low| = ulp(High)/2)", [family](Random& r) {
    // An even significand, so the tie rounds back to High and the pair stays canonical.
    float hi = r.sign() * std::ldexp(static_cast<float>(1.0 + 2 * r.integer(0, (1 << 22) - 1) * 0x1p-23), r.integer(-20, 40));
    Pair a{hi, r.sign() * ulp_of(hi) / 2};
    Pair b = family == F::close ? near(r, a, 2, 30, 1) : r.pair(-20, 40);
    if (family == F::same_sign && (b.hi < 0) != (a.hi < 0)) b = {-b.hi, -b.lo};
    if (family == F::opposite) b = near(r, a, 2, 30, -1);
    if (family == F::ordered && std::fabs(b.hi) > std::fabs(a.hi)) std::swap(a, b);
    return Operands{a, b};
  });
  add(family == F::sum, "exact cancellation (B = -A)", [](Random& r) {
    Pair a = r.pair(-40, 43);
    return Operands{a, {-a.hi, -a.lo}};
  });
  add(family == F::sum || family == F::opposite, "near cancellation (highs a few ULPs apart)", [](Random& r) {
    Pair a = r.pair(-40, 43);
    float b_hi = -a.hi;
    for (int k = r.integer(1, 4); k > 0; --k) b_hi = std::nextafter(b_hi, a.hi < 0 ? 1e38f : -1e38f);
    return Operands{a, to_pair(dd::from(b_hi, (r.uniform() - 0.5) * ulp_of(b_hi)))};
  });
  add(family == F::sum || family == F::opposite, "sloppy-add counterexample", [](Random& r) {
    // Highs cancel to one ULP; the lows cancel that ULP but for an odd number of units 2^-25 ULP
    // below it, so their float sum is a rounding tie: SloppyDWPlusDW rounds it and is off by one
    // unit in 2k+1 (relative error 1/3 for k = 1). Every value is exact and every pair canonical.
    float s = r.sign();
    float one = std::ldexp(1.0f, r.integer(-20, 40)), u = ulp_of(one), unit = std::ldexp(u, -25);
    Pair a{s * (one + u), s * (-u / 2 + unit)};
    Pair b{-s * one, s * (-u / 2 + unit * static_cast<float>(2 * r.integer(1, 7)))};
    return Operands{a, b};
  });
  add(family == F::sum || family == F::same_sign, "straddling a power of two (2^33 - d, 2^33 + d')", [](Random& r) {
    double top = std::ldexp(1.0, 33), d = r.uniform() * 1000, d2 = r.uniform() * 1000;
    return Operands{to_pair(dd::from(top, -d)), to_pair(dd::from(d + d2))};
  });
  add(sums, "huge ratio (2^43 and 2^-40)", [family](Random& r) {
    Pair a = r.pair(42, 43), b = r.pair(-40, -30);
    if (family == F::same_sign && (b.hi < 0) != (a.hi < 0)) b = {-b.hi, -b.lo};
    if (family == F::opposite && (b.hi < 0) == (a.hi < 0)) b = {-b.hi, -b.lo};
    if (family != F::ordered && r.coin()) std::swap(a, b);
    return Operands{a, b};
  });
  add(family == F::ordered, "opposite signs", [](Random& r) {
    Pair a = r.pair(0, 43), b = r.pair(-20, 0);
    if ((a.hi < 0) == (b.hi < 0)) b = {-b.hi, -b.lo};
    return Operands{a, b};
  });
  add(family == F::sum || family == F::same_sign, "2^43 - ulp (the world's edge)", [](Random& r) {
    float edge = std::nextafter(std::ldexp(1.0f, 43), 0.0f);
    return Operands{{edge, static_cast<float>((r.uniform() - 0.5) * ulp_of(edge))}, r.pair(-10, 20)};
  });
  add(family == F::sum || family == F::same_sign, "denormal low parts", [](Random& r) {
    float hi = r.magnitude(-125, -100), lo = std::ldexp(static_cast<float>(r.integer(1, 1000)), -149);
    return Operands{to_pair(dd::from(hi, lo)), to_pair(dd::from(r.magnitude(-125, -100), -lo))};
  });
  if (!cases.empty() && cases.back().name == "denormal low parts") cases.back().domain = NamedCase::Domain::denormal_range;
  add(family == F::close, "object 12.34 cm from a camera 2^42 cm away", [](Random& r) {
    Value camera = dd::from(std::ldexp(1.0, 42), r.uniform() * 1000);
    Value object = dd::add(camera, dd::from(12.34 * r.sign()));
    return Operands{to_pair(object), to_pair(camera)};
  });
  add(family == F::close, "camera and object straddling 2^33", [](Random& r) {
    double top = std::ldexp(1.0, 33);
    return Operands{to_pair(dd::from(top, r.uniform() * 500)), to_pair(dd::from(top, -r.uniform() * 500))};
  });
  add(family == F::close, "equal positions", [](Random& r) {
    Pair a = r.pair(0, 43);
    return Operands{a, a};
  });
  add(family == F::product || family == F::quotient, "powers of two", [](Random& r) {
    return Operands{{r.sign() * std::ldexp(1.0f, r.integer(-40, 40)), 0}, r.pair(-40, 40)};
  });
  add(family == F::product || family == F::quotient, "all-ones significands (Dekker's split edge)", [](Random& r) {
    float ones = 2.0f - std::ldexp(1.0f, -23);
    return Operands{{r.sign() * std::ldexp(ones, r.integer(-40, 40)), 0}, {r.sign() * std::ldexp(ones, r.integer(-40, 40)), 0}};
  });
  // Veltkamp's split needs its constant to be 2^12 + 1: with 2^12 the high part keeps a 13th bit for
  // significands just above 1, and the products of the parts round.
  add(family == F::product || family == F::quotient, "significands just above 1 (Veltkamp's 2^12 + 1)", [](Random& r) {
    auto just_above_one = [&r]() {
      float m = static_cast<float>(1.0 + r.integer(1, (1 << 12) - 1) * 0x1p-23);
      return r.sign() * std::ldexp(m, r.integer(-30, 30));
    };
    return Operands{{just_above_one(), 0}, {just_above_one(), 0}};
  });
  // 4097 * A overflows above 2^128 / 4097 (about 8.3e34): Dekker's split, and every product built
  // on it, gives NaN there even when the result fits (LWC-BRIEF §6).
  add(family == F::product || family == F::quotient, "beyond Dekker's split limit (|A| > 8.3e34, result in range)", [family](Random& r) {
    bool divides = family == F::quotient;
    return Operands{r.pair(117, 126), divides ? r.pair(10, 40) : r.pair(-40, -12)};
  });
  if (!cases.empty() && cases.back().name.starts_with("beyond Dekker")) cases.back().domain = NamedCase::Domain::beyond_split_limit;
  add(family == F::quotient, "A = B", [](Random& r) {
    Pair a = r.pair(-40, 40);
    return Operands{a, a};
  });
  add(family == F::uncanonical, "Low of many ULPs of High (not canonical)", [](Random& r) {
    float hi = r.sign() * r.magnitude(-20, 43);
    return Operands{{hi, static_cast<float>(r.sign() * ulp_of(hi) * r.integer(2, 1 << 20))}, {}};
  });
  add(family == F::uncanonical, "Low cancelling High", [](Random& r) {
    float hi = r.sign() * r.magnitude(-20, 43);
    return Operands{{hi, -hi * static_cast<float>(1.0 - r.uniform() * 0x1p-10)}, {}};
  });
  // The tile size is 2^21 here, on the CPU, whatever the library defines: a wrong size in the
  // library cannot move the reference with it.
  add(family == F::tile_offset, "offset of three tiles (not normalised)", [](Random& r) {
    return Operands{{static_cast<float>(r.integer(-(1 << 22), 1 << 22)), 0}, {static_cast<float>(r.sign() * (3 * kTile + r.uniform() * 1000)), 0}};
  });
  add(family == F::tile_offset, "half-tile offset", [](Random& r) {
    return Operands{{static_cast<float>(r.integer(-(1 << 22), 1 << 22)), 0}, {static_cast<float>(r.sign() * kTile / 2), 0}};
  });
  add(family == F::world, "half-tile tie ((k + 0.5) * 2^21)", [](Random& r) {
    return Operands{to_pair(dd::from((r.integer(-(1 << 21), 1 << 21) + 0.5) * kTile)), {}};
  });
  add(family == F::world, "tile edge (k * 2^21 +- a little)", [](Random& r) {
    return Operands{to_pair(dd::from(r.integer(-(1 << 21), 1 << 21) * kTile, r.sign() * r.uniform() * 0.01)), {}};
  });
  add(family == F::world, "2^43 - ulp", [](Random& r) {
    float edge = std::nextafter(std::ldexp(1.0f, 43), 0.0f);
    return Operands{{r.sign() * edge, static_cast<float>((r.uniform() - 0.5) * ulp_of(edge))}, {}};
  });
  add(family == F::positive, "perfect squares", [](Random& r) {
    double k = r.integer(1, 4000);
    return Operands{{static_cast<float>(k * k), 0}, {}};
  });
  add(family == F::positive, "2^43 - ulp", [](Random& r) {
    float edge = std::nextafter(std::ldexp(1.0f, 43), 0.0f);
    return Operands{{edge, static_cast<float>((r.uniform() - 0.5) * ulp_of(edge))}, {}};
  });
  return cases;
}

Operands random_operands(Random& r, InputFamily family) {
  using F = InputFamily;
  switch (family) {
    case F::sum: {
      Pair a = r.pair(-40, 43);
      return {a, r.coin() ? r.pair(-40, 43) : near(r, a, 1, 30, r.sign())};
    }
    case F::ordered: {
      Pair a = r.pair(-40, 43), b = r.pair(-40, 43);
      if (std::fabs(a.hi) < std::fabs(b.hi)) std::swap(a, b);
      return {a, b};
    }
    case F::same_sign: {
      Pair a = r.pair(-40, 43), b = r.coin() ? r.pair(-40, 43) : near(r, a, 1, 30, 1);
      if ((a.hi < 0) != (b.hi < 0)) b = {-b.hi, -b.lo};
      return {a, b};
    }
    case F::opposite: {
      Pair a = r.pair(-40, 43);
      return {a, near(r, a, 1, 30, -1)};
    }
    case F::close: {
      Pair a = r.pair(-10, 43);
      return {a, near(r, a, 2, 40, 1)};
    }
    case F::product:
    case F::quotient: return {r.pair(-40, 40), r.pair(-40, 40)};
    case F::positive: {
      Pair a = r.pair(-60, 60);
      return {a.hi < 0 ? Pair{-a.hi, -a.lo} : a, {}};
    }
    case F::tile_offset:
      return {{static_cast<float>(r.integer(-(1 << 22), 1 << 22)), 0}, {static_cast<float>((r.uniform() - 0.5) * kTile), 0}};
    case F::world: return {r.pair(-10, 43), {}};
    case F::uncanonical: {
      float hi = r.sign() * r.magnitude(-40, 43);
      return {{hi, r.sign() * std::ldexp(std::fabs(hi), -r.integer(0, 30))}, {}};
    }
  }
  return {};
}

// The inputs of one operation: each adversarial case 256 times, then random ones; float
// operands drop their low part.
std::vector<Operands> make_inputs(const LibraryOp& op, size_t count) {
  Random r(0x6c7763706f7274ull);  // fixed: the same inputs every run
  std::vector<NamedCase> cases = adversarial_cases(op.inputs);
  std::vector<Operands> out;
  for (size_t c = 0; c < cases.size(); ++c)
    for (int i = 0; i < 256; ++i) {
      Operands o = cases[c].make(r);
      o.case_id = static_cast<int>(c) + 1;
      out.push_back(o);
    }
  while (out.size() < count) out.push_back(random_operands(r, op.inputs));
  out.resize(std::max(count, out.size()));
  for (Operands& o : out) {
    if (!op.pair_operands[0]) o.a = to_pair(dd::from(o.a.hi));
    if (!op.pair_operands[1]) o.b = to_pair(dd::from(o.b.hi));
    if (op.operands < 2) o.b = {};
  }
  return out;
}

// ---- Judging ------------------------------------------------------------------------------

double allowed_error(const Bound& bound, Value exact, const Operands& in) {
  double magnitude = std::fabs(exact.approx());
  double a = std::fabs(in.a.value().approx()), b = std::fabs(in.b.value().approx());
  switch (bound.kind) {
    case Bound::exact: return 0;
    case Bound::relative: return bound.u2 * kU2 * magnitude;
    case Bound::rounded: {
      double scale = bound.scale == Bound::sum ? a + b : bound.scale == Bound::product ? a * b : a / b;
      return bound.roundings * kU * magnitude + bound.u2 * kU2 * scale;
    }
    case Bound::offset: return kU * 0x1p20;
    case Bound::none: return std::numeric_limits<double>::infinity();
  }
  return 0;
}

std::string describe_pair(const Pair& p) { return fmt::format("{:.9g} + {:.9g}", p.hi, p.lo); }

std::string worst_case_text(const LibraryOp& op, const Operands& in, Value exact, float hi, float lo) {
  std::vector<NamedCase> cases = adversarial_cases(op.inputs);
  std::string name = in.case_id == 0 ? "random" : cases[in.case_id - 1].name;
  std::string operands = fmt::format("A = {}", describe_pair(in.a));
  if (op.operands > 1) operands += fmt::format(", B = {}", describe_pair(in.b));
  return fmt::format("case '{}': {}; expected {:.17g}, got {}", name, operands, exact.approx(),
                     op.pair_result ? describe_pair({hi, lo}) : fmt::format("{:.9g}", hi));
}

std::string kernel_body(const LibraryOp& op, Lang lang) {
  const std::string& call = lang == Lang::glsl && !op.glsl_call.empty() ? op.glsl_call : op.call;
  std::string result = op.tile_result   ? "float Tile;\n\tfloat Offset;\n\t" + call + ";\n\tOUT(0, Tile);\n\tOUT(1, Offset);"
                       : op.pair_result ? "FDFScalar R = " + call + ";\n\tOUT(0, R.High);\n\tOUT(1, R.Low);"
                                        : "float R = " + call + ";\n\tOUT(0, R);\n\tOUT(1, 0.0);";
  return "\tFDFScalar A = MakeDFScalar(IN(0), IN(1));\n\tFDFScalar B = MakeDFScalar(IN(2), IN(3));\n"
         "\tfloat a = IN(0);\n\tfloat b = IN(2);\n\t" + result;
}

// `dekker`: the operation multiplies with Dekker's split here, so inputs beyond its limit are
// outside the library's domain; `flushes`: the driver flushes denormals, so denormal low parts
// are. Both are counted apart, not judged against the bound.
OpMeasurement measure(const LibraryOp& op, const std::vector<Operands>& inputs, const std::vector<float>& out, bool dekker,
                      bool flushes) {
  OpMeasurement m;
  m.inputs = inputs.size();
  std::vector<NamedCase> cases = adversarial_cases(op.inputs);
  std::vector<double> relative;
  relative.reserve(inputs.size());
  size_t worst = 0;
  double worst_score = -1;
  for (size_t i = 0; i < inputs.size(); ++i) {
    const Operands& in = inputs[i];
    Value exact = op.reference(in.a.value(), in.b.value());
    float hi = out[2 * i], lo = out[2 * i + 1];
    Value got = op.tile_result ? dd::add(dd::from(static_cast<double>(hi) * kTile), dd::from(lo)) : dd::from(hi, lo);
    double error = std::fabs(dd::sub(got, exact).approx());
    if (!std::isfinite(hi) || !std::isfinite(lo)) error = std::numeric_limits<double>::infinity();
    double magnitude = std::fabs(exact.approx());
    double rel = error == 0 ? 0 : magnitude == 0 ? std::numeric_limits<double>::infinity() : error / magnitude;
    double allowed = allowed_error(op.bound, exact, in);
    double ratio = error == 0 ? 0 : allowed == 0 ? std::numeric_limits<double>::infinity() : error / allowed;
    using D = NamedCase::Domain;
    D domain = in.case_id > 0 ? cases[in.case_id - 1].domain : D::inside;
    OpMeasurement::Outside* outside = domain == D::beyond_split_limit && dekker ? &m.beyond_split_limit
                                      : domain == D::denormal_range && flushes ? &m.denormal_range
                                                                               : nullptr;
    if (outside) {
      ++outside->inputs;
      bool canonical = !op.pair_result || !std::isfinite(hi) || hi + lo == hi;
      if (!(ratio <= 1 && canonical) && outside->misses++ == 0) outside->example = worst_case_text(op, in, exact, hi, lo);
      continue;
    }
    if (op.pair_result && std::isfinite(hi) && hi + lo != hi) ++m.non_canonical;
    if (op.tile_result && (hi != std::nearbyint(hi) || std::fabs(lo) > kTile / 2 + std::fabs(in.a.lo) + 1)) ++m.non_canonical;
    relative.push_back(rel);
    m.max_relative = std::max(m.max_relative, rel);
    m.max_bound_ratio = std::max(m.max_bound_ratio, ratio);
    double score = op.bound.kind == Bound::none ? rel : ratio;
    if (score > worst_score) worst_score = score, worst = i;
  }
  if (!relative.empty()) {
    std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
    m.median_relative = relative[relative.size() / 2];
    const Operands& in = inputs[worst];
    m.worst = worst_case_text(op, in, op.reference(in.a.value(), in.b.value()), out[2 * worst], out[2 * worst + 1]);
  }
  return m;
}

Value add_ref(Value a, Value b) { return dd::add(a, b); }
Value sub_ref(Value a, Value b) { return dd::sub(a, b); }
Value mul_ref(Value a, Value b) { return dd::mul(a, b); }
Value div_ref(Value a, Value b) { return dd::div(a, b); }
Value sqrt_ref(Value a, Value) { return dd::sqrt(a); }
Value value_ref(Value a, Value) { return a; }
Value tile_ref(Value tile, Value offset) { return dd::add(dd::mul(tile, dd::from(kTile)), offset); }
Value twice_difference_ref(Value a, Value b) { return dd::mul(dd::sub(a, b), dd::from(2)); }

// The matrix operations run with one fixed matrix whose products are exact in float32, so the
// reference is plain: in the engine's row-vector convention it maps local (x, y, z) to
// (-y, 2x, z/2). Its literal lists the same elements in both languages (HLSL's constructor takes
// rows, GLSL's columns, and GLSL multiplies matrix * vector): element [1][0] is -1, [0][1] is 2.
const char* kMatrixHlsl = "float4x4(0, 2, 0, 0, -1, 0, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1)";
const char* kMatrixGlsl = "mat4(0, 2, 0, 0, -1, 0, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1)";

// `text` in HLSL and its GLSL spelling: float3 -> vec3, the matrix literal.
std::string glsl_spelling(std::string text) {
  for (size_t at; (at = text.find("float3(")) != std::string::npos;) text.replace(at, 6, "vec3");
  for (size_t at; (at = text.find(kMatrixHlsl)) != std::string::npos;) text.replace(at, std::strlen(kMatrixHlsl), kMatrixGlsl);
  return text;
}

LibraryOp op(std::string call, bool pa, bool pb, bool pair_result, InputFamily inputs, Bound bound,
             Value (*reference)(Value, Value), int operands = 2) {
  LibraryOp o;
  o.call = std::move(call);
  o.pair_operands[0] = pa;
  o.pair_operands[1] = pb;
  o.pair_result = pair_result;
  o.inputs = inputs;
  o.bound = std::move(bound);
  o.reference = reference;
  o.operands = operands;
  return o;
}

}  // namespace

const std::vector<LibraryOp>& library_ops() {
  using F = InputFamily;
  static const std::vector<LibraryOp> ops = [] {
    Bound exact{Bound::exact, 0, Bound::sum, "exact"};
    auto relative = [](double u2, std::string text) { return Bound{Bound::relative, u2, Bound::sum, std::move(text)}; };
    auto rounded = [](double u2, Bound::Scale scale, std::string text) { return Bound{Bound::rounded, u2, scale, std::move(text)}; };
    std::vector<LibraryOp> v;
    v.push_back(op("DFTwoSum(a, b)", false, false, true, F::sum, exact, add_ref));
    v.push_back(op("DFFastTwoSum(a, b)", false, false, true, F::ordered, {Bound::exact, 0, Bound::sum, "exact when |a| >= |b|"}, add_ref));
    v.push_back(op("DFTwoProductDekker(a, b)", false, false, true, F::product, exact, mul_ref));
    LibraryOp fma = op("DFTwoProductFMA(a, b)", false, false, true, F::product, {Bound::exact, 0, Bound::sum, "exact with a fused fma"}, mul_ref);
    fma.needs_fused_fma = true;
    v.push_back(fma);
    v.push_back(op("DFTwoProduct(a, b)", false, false, true, F::product, exact, mul_ref));
    v.push_back(op("DFAdd(A, b)", true, false, true, F::sum, relative(2, "2u^2 (DWPlusFP)"), add_ref));
    v.push_back(op("DFAdd(A, B)", true, true, true, F::sum, relative(3 + 13 * kU, "3u^2 + 13u^3 (AccurateDWPlusDW)"), add_ref));
    v.push_back(op("DFSubtract(A, B)", true, true, true, F::sum, relative(3 + 13 * kU, "3u^2 + 13u^3 (AccurateDWPlusDW)"), sub_ref));
    v.push_back(op("DFFastAdd(A, B)", true, true, true, F::same_sign, relative(3, "3u^2 for same signs (SloppyDWPlusDW)"), add_ref));
    v.push_back(op("DFFastAdd(A, B)", true, true, true, F::opposite, {Bound::none, 0, Bound::sum, "none for opposite signs"}, add_ref));
    v.push_back(op("DFMultiply(A, b)", true, false, true, F::product, relative(2, "2u^2 (DWTimesFP)"), mul_ref));
    v.push_back(op("DFMultiply(A, B)", true, true, true, F::product, relative(5, "5u^2 (DWTimesDW)"), mul_ref));
    v.push_back(op("DFDivide(A, b)", true, false, true, F::quotient, relative(3, "3u^2 (DWDivFP)"), div_ref));
    v.push_back(op("DFDivide(A, B)", true, true, true, F::quotient, relative(10, "~10u^2 (DWDivDW)"), div_ref));
    v.push_back(op("DFSqrt(A)", true, false, true, F::positive, {Bound::none, 0, Bound::sum, "none published"}, sqrt_ref, 1));
    v.push_back(op("DFDemote(A)", true, false, false, F::uncanonical, rounded(0, Bound::sum, "one rounding of High + Low"), value_ref, 1));
    v.push_back(op("DFFromTileOffset(a, b)", false, false, true, F::tile_offset, exact, tile_ref));
    LibraryOp to_tile = op("DFToTileOffset(A, Tile, Offset)", true, false, false, F::world,
                           {Bound::offset, 0, Bound::sum, "one rounding of the offset (u * 2^20)"}, value_ref, 1);
    to_tile.tile_result = true;
    v.push_back(to_tile);
    v.push_back(op("DFAddDemote(A, b)", true, false, false, F::sum, rounded(2, Bound::sum, "~u"), add_ref));
    v.push_back(op("DFAddDemote(A, B)", true, true, false, F::sum, rounded(3, Bound::sum, "~u"), add_ref));
    v.push_back(op("DFSubtractDemote(A, B)", true, true, false, F::sum, rounded(3, Bound::sum, "~u"), sub_ref));
    v.push_back(op("DFMultiplyDemote(A, b)", true, false, false, F::product, rounded(3, Bound::product, "~u"), mul_ref));
    v.push_back(op("DFMultiplyDemote(A, B)", true, true, false, F::product, rounded(4, Bound::product, "~u"), mul_ref));
    v.push_back(op("DFDivideDemote(A, b)", true, false, false, F::quotient, rounded(4, Bound::quotient, "~u"), div_ref));
    v.push_back(op("DFFastLocalSubtractDemote(A, B)", true, true, false, F::close,
                   rounded(2, Bound::sum, "~u of the difference (same sign, close)"), sub_ref));
    // Translated world and the matrices, each read through one component (see kMatrixHlsl).
    auto spelled = [](LibraryOp o, std::string label) {
      o.glsl_call = glsl_spelling(o.call);
      o.label = std::move(label);
      return o;
    };
    std::string matrix = kMatrixHlsl;
    // Two roundings (the highs' sum, exact only within a factor of 2, then the result), plus the lows'.
    Bound fast_translated = rounded(2, Bound::sum, "~2u (exact highs near the camera)");
    fast_translated.roundings = 2;
    v.push_back(spelled(op("DFFastToTranslatedWorld(MakeDFVector3(float3(A.High, 0, 0), float3(A.Low, 0, 0)), "
                           "MakeDFVector3(float3(B.High, 0, 0), float3(B.Low, 0, 0))).x",
                           true, true, false, F::opposite, fast_translated, add_ref),
                        "DFFastToTranslatedWorld(A, B).x"));
    // FDFMatrix adds its PostTranslation after M: x = PostTranslation.x - local.y, exact.
    std::string to_world = "DFMultiply(float3(0.75, b, -1.5), MakeDFMatrix(float3(a, 3.0, 5.0), " + matrix + "))";
    v.push_back(spelled(op("MakeDFScalar(" + to_world + ".High.x, " + to_world + ".Low.x)", false, false, true, F::sum,
                           {Bound::exact, 0, Bound::sum, "exact (PostTranslation after M)"}, sub_ref),
                        "DFMultiply((.75, b, -1.5), FDFMatrix(a)).x"));
    // FDFInverseMatrix subtracts its PreTranslation before M: y = 2 (P.x - PreTranslation.x).
    v.push_back(spelled(op("DFMultiplyDemote(MakeDFVector3(float3(A.High, 1.0, 2.0), float3(A.Low, 0, 0)), "
                           "MakeDFInverseMatrix(float3(b, 0, 0), " + matrix + ")).y",
                           true, false, false, F::sum, rounded(4, Bound::sum, "~u (PreTranslation before M)"), twice_difference_ref),
                        "DFMultiplyDemote(A, FDFInverseMatrix(b)).y"));
    // Local -> translated world: the translations meet in double-float; local (0.75, 0, -1.5) maps
    // to x = 0, so x is PreViewTranslation.x + PostTranslation.x rounded once.
    v.push_back(spelled(op("DFTransformLocalToTranslatedWorld(float3(0.75, 0, -1.5), MakeDFMatrix(float3(b, 0, 0), " + matrix +
                           "), MakeDFVector3(float3(A.High, 0, 0), float3(A.Low, 0, 0))).x",
                           true, false, false, F::opposite, rounded(2, Bound::sum, "~u of the camera-relative offset"), add_ref),
                        "DFTransformLocalToTranslatedWorld(0, FDFMatrix(b), A).x"));
    return v;
  }();
  return ops;
}

std::map<std::string, std::string> library_faults(const LibraryAccuracy& accuracy, Lang lang) {
  std::map<std::string, std::string> faults;
  for (const OpReport& r : accuracy.ops) {
    auto m = r.by_lang.find(lang);
    if (m == r.by_lang.end() || m->second.status != "fail") continue;
    std::string& why = faults[r.op->call.substr(0, r.op->call.find('('))];
    if (why.empty()) why = fmt::format("{}: {}", r.op->name(), m->second.worst);
  }
  return faults;
}

std::vector<FloatOperands> float_operands(InputFamily family, size_t count, bool flushes_denormals) {
  Random r(0x6566742d6f7073ull);
  std::vector<NamedCase> cases = adversarial_cases(family);
  std::vector<FloatOperands> out;
  for (size_t c = 0; c < cases.size() && out.size() < count; ++c)
    for (int i = 0; i < 256 && cases[c].domain != NamedCase::Domain::beyond_split_limit &&
                    !(flushes_denormals && cases[c].domain == NamedCase::Domain::denormal_range);
         ++i) {
      Operands o = cases[c].make(r);
      out.push_back({o.a.hi, o.b.hi, static_cast<int>(c)});
    }
  while (out.size() < count) {
    Operands o = random_operands(r, family);
    out.push_back({o.a.hi, o.b.hi, -1});
  }
  out.resize(count);
  return out;
}

std::vector<std::string> adversarial_case_names(InputFamily family) {
  std::vector<std::string> out;
  for (const NamedCase& c : adversarial_cases(family)) out.push_back(c.name);
  return out;
}

bool LibraryAccuracy::failed() const {
  for (const auto& [lang, losses] : contraction_losses)
    if (!losses.empty()) return true;
  for (const OpReport& r : ops)
    for (const auto& [lang, m] : r.by_lang)
      if (m.status == "fail" || m.status.rfind("error", 0) == 0) return true;
  return false;
}

LibraryAccuracy check_library(WorkerDevice& device, const DriverProbes& probes, const LibraryCheckOptions& options) {
  LibraryAccuracy result;
  const std::vector<LibraryOp>& ops = options.ops.empty() ? library_ops() : options.ops;
  std::vector<std::pair<std::string, std::string>> defines = {{"LWC_DF_FUSED_FMA", probes.fuses_fma() ? "1" : "0"}};
  for (Lang lang : options.langs) {
    auto custom = options.library.find(lang);
    std::string library = custom != options.library.end() ? custom->second : full_library_text(lang);
    std::set<std::string> losses, checked;
    result.contraction_losses[lang];
    for (size_t i = 0; i < ops.size(); ++i) {
      const LibraryOp& op = ops[i];
      if (result.ops.size() <= i) result.ops.push_back({&op, {}});
      OpMeasurement& m = result.ops[i].by_lang[lang];
      KernelSpec spec;
      spec.lang = lang;
      spec.name = fmt::format("{}-{}", op.call.substr(0, op.call.find('(')), lang == Lang::glsl ? "glsl" : "hlsl");
      spec.declarations = library;
      spec.body = kernel_body(op, lang);
      spec.in_stride = 4;
      spec.out_stride = 2;
      CompileResult compiled = compile_kernel(spec, defines);
      if (!compiled.ok) {
        m.status = "error: the kernel does not compile: " + format_messages(compiled);
        continue;
      }
      SpirvSummary spirv = inspect_spirv(compiled.spirv);
      for (const std::string& loss : contraction_losses(spirv)) losses.insert(loss);
      for (const SpirvFunction& f : spirv.functions)
        if (error_free_functions().count(f.name)) checked.insert(f.signature);

      size_t count = (options.inputs + kKernelGroupSize - 1) / kKernelGroupSize * kKernelGroupSize;
      std::vector<Operands> inputs = make_inputs(op, count);
      std::vector<float> packed;
      packed.reserve(inputs.size() * 4);
      for (const Operands& o : inputs) packed.insert(packed.end(), {o.a.hi, o.a.lo, o.b.hi, o.b.lo});
      std::vector<std::vector<uint8_t>> buffers = {to_bytes(packed), std::vector<uint8_t>(inputs.size() * 2 * sizeof(float))};
      DispatchTiming timing;
      if (std::string why = device.run(compiled.spirv, buffers, static_cast<uint32_t>(inputs.size() / kKernelGroupSize), 1, &timing);
          !why.empty()) {
        m.status = "error: " + why;
        continue;
      }
      result.pipeline_seconds += timing.pipeline_seconds;
      for (double s : timing.dispatch_seconds) result.dispatch_seconds += s;
      bool dekker = (op.inputs == InputFamily::product || op.inputs == InputFamily::quotient) &&
                    (op.call.find("Dekker") != std::string::npos || (!probes.fuses_fma() && !op.needs_fused_fma));
      m = measure(op, inputs, from_bytes<float>(buffers[1]), dekker, !probes.keeps_denormals());
      if (op.needs_fused_fma && !probes.fuses_fma())
        m.status = "reported: needs a fused fma, and the probe shows this driver does not fuse it";
      else if (op.bound.kind == Bound::none)
        m.status = "reported: no bound (" + op.bound.text + ")";
      else
        m.status = m.max_bound_ratio <= 1 && m.non_canonical == 0 ? "pass" : "fail";
    }
    result.contraction_losses[lang].assign(losses.begin(), losses.end());
    result.error_free_functions_checked[lang] = static_cast<int>(checked.size());
  }
  return result;
}

}  // namespace lwc
