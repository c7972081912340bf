// A metal-cpp style pipeline set-up (a few declarations stand in for metal-cpp's headers) that
// compiles shaders doing DoubleFloat arithmetic.
namespace MTL {
enum MathMode { MathModeSafe = 0, MathModeRelaxed = 1, MathModeFast = 2 };
struct CompileOptions {
  static CompileOptions* alloc();
  CompileOptions* init();
  void setFastMathEnabled(bool enabled);
  void setMathMode(MathMode mode);
};
}  // namespace MTL

MTL::CompileOptions* FastOptions()
{
  MTL::CompileOptions* options = MTL::CompileOptions::alloc()->init();
  options->setFastMathEnabled(true);
  return options;
}

MTL::CompileOptions* SafeOptions()
{
  MTL::CompileOptions* options = MTL::CompileOptions::alloc()->init();
  options->setMathMode(MTL::MathModeSafe);
  return options;
}
