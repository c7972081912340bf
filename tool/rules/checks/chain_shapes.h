#pragma once
// The shapes a translated-world chain moves through, and the file's functions and calls as the
// chain rewrites of lwc-float-world-position meet them: which expression around a use is still
// the same point, which vectors are no positions, who calls a function and which parameter an
// argument lands in, and the plan's own bookkeeping.
#include <string>
#include <string_view>
#include <vector>

#include "rules/checks/util.h"

namespace lwc::checks {

// `V += PreViewTranslation;` (or `V.xyz += ...`) as a statement of the function's own body, not
// under a branch or a loop: the statement, or -1.
int rebase_statement(const CheckContext& ctx, int use);

// The largest expression around a use that is still the same point, moved by the same
// translation: through parentheses, `.xyz`, a perspective divide (`H.xyz / H.w`), and a small
// offset added to it or taken from it.
int climb_point(const CheckContext& ctx, int n);

// `float4(P, W)` around P (its first argument) with W no homogeneous 0 or 1: the call, or -1.
int packed_point(const SyntaxTree& t, int point);

// A kind that is a point in some frame (absolute, translated, or the camera offset).
bool is_position(Kind k);

// A vector that is not a position: small by its kind, or built from names that say so, unit
// vectors (`normalize(..)`) and locals holding such vectors, scaled by scalars and numbers
// (`Normal * Bias`, `L * MaxDistance`).
bool small_vector(const CheckContext& ctx, int n);
// The other term `other` of `point op other` (op "+" or "-", `sum` the whole expression) moves the
// point by an offset: a small vector, a scalar, or, in a sum, a vector in which no position is known
// and no name calls a point (`P + DepthBias`): two points added make no point, unless averaged
// (`(A + B) * 0.5`), which the sum must not be. A difference takes only an offset its name says.
bool point_offset(const CheckContext& ctx, int other, std::string_view op, int sum);
// A point moved in place by an offset (`P -= Bias * Dir`, `P.z += Height` with Height a scalar):
// the statement keeps it a point of the same space.
bool shifted_in_place(const CheckContext& ctx, int use);

// `X + PreViewTranslation` (either order, through parentheses) around an expression: the sum, or -1.
int pre_view_sum(const CheckContext& ctx, int expr);

// `text` (which starts at `offset` in the file) with edits inside it applied.
std::string spliced(std::string text, uint32_t offset, std::vector<Edit> edits);

// Some edit of the plan rewrites `span` (or text around it).
bool covered(const RewritePlan& plan, Span span);

// The calls of function `fn` in this file: its name, with as many arguments as it takes.
std::vector<int> calls_to(const SyntaxTree& t, int fn);


void collect_returns(const SyntaxTree& t, int node, std::vector<int>& out);

// A file compiled as one program (an Unreal .usf, a GLSL stage): nothing outside it calls its functions.
bool whole_program(const SyntaxTree& t);

// The parameter of a function of this file that an argument is passed to, or -1.
int parameter_of(const CheckContext& ctx, int argument);
// A use that stores into its variable: assigned (whole or a part: `P.z += ..`), stepped, or
// passed to an `out`/`inout` parameter of this file.
bool stores_into(const CheckContext& ctx, int use);

// The `out` parameter (not `inout`: that reads the value too) an argument is passed to, or -1.
int out_parameter_of(const CheckContext& ctx, int argument);

int calls_of(const SyntaxTree& t, std::string_view name);

bool moving(const RewritePlan& plan, int var);

}  // namespace lwc::checks
