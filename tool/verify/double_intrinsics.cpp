#include "verify/double_intrinsics.h"

#include <fmt/format.h>

namespace lwc {

namespace {

// Component-wise forms: scalar `body` (in terms of x, y, z) for double, then loops for vectors.
struct Componentwise {
  const char* name;
  int arity;
  const char* body;
};

// 2^60, 2^30 and 2^52 are powers of two: exact as literals of any width.
constexpr Componentwise kComponentwise[] = {
    // Square root from a float32 seed and two Newton steps (float's 2^-24 becomes 2^-48, then
    // double's own rounding), with the argument scaled by powers of four into float's range.
    {"sqrt", 1,
     "if (x != x || x == 0.0) return x;\n"
     "  if (x < 0.0) return (x - x) / (x - x);\n"
     "  if (x * 0.5 == x) return x;\n"
     "  double s = 1.0;\n"
     "  while (x > 1152921504606846976.0) { x /= 1152921504606846976.0; s *= 1073741824.0; }\n"
     "  while (x < 1.0 / 1152921504606846976.0) { x *= 1152921504606846976.0; s /= 1073741824.0; }\n"
     "  double r = (double)sqrt((float)x);\n"
     "  r = 0.5 * (r + x / r);\n"
     "  r = 0.5 * (r + x / r);\n"
     "  return r * s;"},
    {"rsqrt", 1, "return 1.0 / lwc_d_sqrt(x);"},
    // Round to the nearest integer, ties to even: adding and subtracting 2^52 leaves no fraction
    // bits (precise: the driver must not fold the pair away).
    {"round", 1,
     "if (!(abs(x) < 4503599627370496.0) || x == 0.0) return x;\n"
     "  precise double r = (abs(x) + 4503599627370496.0) - 4503599627370496.0;\n"
     "  return x < 0.0 ? -r : r;"},
    {"floor", 1, "double r = lwc_d_round(x);\n  return r > x ? r - 1.0 : r;"},
    {"ceil", 1, "double r = lwc_d_round(x);\n  return r < x ? r + 1.0 : r;"},
    {"trunc", 1, "return x < 0.0 ? lwc_d_ceil(x) : lwc_d_floor(x);"},
    {"frac", 1, "return x - lwc_d_floor(x);"},
    {"sign", 1, "return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0;"},
    {"saturate", 1, "return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;"},
    {"min", 2, "return y < x ? y : x;"},
    {"max", 2, "return y > x ? y : x;"},
    {"step", 2, "return y >= x ? 1.0 : 0.0;"},
    {"fmod", 2, "return x - y * lwc_d_trunc(x / y);"},
    {"clamp", 3, "return lwc_d_min(lwc_d_max(x, y), z);"},
    {"lerp", 3, "return x + (y - x) * z;"},
    {"smoothstep", 3, "double t = lwc_d_saturate((z - x) / (y - x));\n  return t * t * (3.0 - 2.0 * t);"},
};

std::string parameters(const std::string& type, int arity) {
  std::string out;
  for (int i = 0; i < arity; ++i) out += fmt::format("{}{} {}", i ? ", " : "", type, "xyz"[i]);
  return out;
}

}  // namespace

const std::set<std::string, std::less<>>& narrowed_hlsl_intrinsics() {
  static const std::set<std::string, std::less<>> names = [] {
    std::set<std::string, std::less<>> out = {"dot", "length", "distance", "normalize", "cross", "reflect", "faceforward", "any", "all"};
    for (const Componentwise& c : kComponentwise) out.insert(c.name);
    return out;
  }();
  return names;
}

std::string hlsl_double_intrinsics() {
  std::string out;
  for (const Componentwise& c : kComponentwise) {
    out += fmt::format("double lwc_d_{}({}) {{\n  {}\n}}\n", c.name, parameters("double", c.arity), c.body);
    for (int n = 2; n <= 4; ++n) {
      std::string args;
      for (int i = 0; i < c.arity; ++i) args += fmt::format("{}{}[i]", i ? ", " : "", "xyz"[i]);
      out += fmt::format("double{0} lwc_d_{1}({2}) {{ double{0} r; for (int i = 0; i < {0}; ++i) r[i] = lwc_d_{1}({3}); return r; }}\n",
                         n, c.name, parameters(fmt::format("double{}", n), c.arity), args);
    }
  }
  out += "double lwc_d_dot(double x, double y) { return x * y; }\n"
         "double lwc_d_length(double x) { return abs(x); }\n"
         "double lwc_d_distance(double x, double y) { return abs(x - y); }\n"
         "double lwc_d_normalize(double x) { return x / abs(x); }\n"
         "bool lwc_d_any(double x) { return x != 0.0; }\n"
         "bool lwc_d_all(double x) { return x != 0.0; }\n";
  for (int n = 2; n <= 4; ++n) {
    out += fmt::format(
        "double lwc_d_dot(double{0} x, double{0} y) {{ double r = 0.0; for (int i = 0; i < {0}; ++i) r += x[i] * y[i]; return r; }}\n"
        "double lwc_d_length(double{0} x) {{ return lwc_d_sqrt(lwc_d_dot(x, x)); }}\n"
        "double lwc_d_distance(double{0} x, double{0} y) {{ return lwc_d_length(x - y); }}\n"
        "double{0} lwc_d_normalize(double{0} x) {{ return x / lwc_d_length(x); }}\n"
        "double{0} lwc_d_reflect(double{0} i, double{0} n) {{ return i - 2.0 * lwc_d_dot(n, i) * n; }}\n"
        "double{0} lwc_d_faceforward(double{0} n, double{0} i, double{0} g) {{ return lwc_d_dot(g, i) < 0.0 ? n : -n; }}\n"
        "bool lwc_d_any(double{0} x) {{ bool r = false; for (int i = 0; i < {0}; ++i) r = r || x[i] != 0.0; return r; }}\n"
        "bool lwc_d_all(double{0} x) {{ bool r = true; for (int i = 0; i < {0}; ++i) r = r && x[i] != 0.0; return r; }}\n",
        n);
  }
  out += "double3 lwc_d_cross(double3 a, double3 b) { return double3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }\n";
  // mul and transpose, row by row as HLSL defines them (row vectors on the left, rows of the matrix).
  for (int n = 2; n <= 4; ++n)
    for (int m = 2; m <= 4; ++m) {
      out += fmt::format("double{1} mul(double{0} v, double{0}x{1} a) {{ double{1} r = 0; for (int i = 0; i < {0}; ++i) r += v[i] * a[i]; return r; }}\n", n, m);
      out += fmt::format("double{0} mul(double{0}x{1} a, double{1} v) {{ double{0} r; for (int i = 0; i < {0}; ++i) {{ double s = 0; "
                         "for (int j = 0; j < {1}; ++j) s += a[i][j] * v[j]; r[i] = s; }} return r; }}\n", n, m);
      out += fmt::format("double{1}x{0} transpose(double{0}x{1} a) {{ double{1}x{0} r; for (int i = 0; i < {0}; ++i) "
                         "for (int j = 0; j < {1}; ++j) r[j][i] = a[i][j]; return r; }}\n", n, m);
    }
  for (int n = 2; n <= 4; ++n)
    for (int k = 2; k <= 4; ++k)
      for (int m = 2; m <= 4; ++m)
        out += fmt::format("double{0}x{2} mul(double{0}x{1} a, double{1}x{2} b) {{ double{0}x{2} r; for (int i = 0; i < {0}; ++i) "
                           "r[i] = mul(a[i], b); return r; }}\n", n, k, m);
  return out;
}

}  // namespace lwc
