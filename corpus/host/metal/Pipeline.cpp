// A metal-cpp style pipeline set-up (a few declarations stand in for metal-cpp's headers) that
// compiles shaders doing DoubleFloat arithmetic.
namespace NS {
struct String;
struct Error;
}  // namespace NS

namespace MTL {
enum MathMode { MathModeSafe = 0, MathModeRelaxed = 1, MathModeFast = 2 };
struct CompileOptions {
  static CompileOptions* alloc();
  CompileOptions* init();
  void setFastMathEnabled(bool enabled);
  void setMathMode(MathMode mode);
  void release();
};
struct Library;
struct Device {
  Library* newLibrary(const NS::String* source, const CompileOptions* options, NS::Error** error);
};
}  // namespace MTL

void Configure(MTL::CompileOptions* options);

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

// Relaxed math (Apple silicon's default) reassociates as well.
MTL::CompileOptions* RelaxedOptions()
{
  MTL::CompileOptions* options = MTL::CompileOptions::alloc()->init();
  options->setMathMode(MTL::MathModeRelaxed);
  return options;
}

// No options: Metal's defaults, fast math on.
MTL::Library* BuildWithDefaults(MTL::Device* device, const NS::String* source, NS::Error** error)
{
  return device->newLibrary(source, nullptr, error);
}

// Options made here and never switched to safe math.
MTL::Library* BuildWithFreshOptions(MTL::Device* device, const NS::String* source, NS::Error** error)
{
  MTL::CompileOptions* options = MTL::CompileOptions::alloc()->init();
  MTL::Library* library = device->newLibrary(source, options, error);
  options->release();
  return library;
}

// Right: safe math. And options set up elsewhere are not judged here.
MTL::Library* BuildSafe(MTL::Device* device, const NS::String* source, NS::Error** error)
{
  MTL::CompileOptions* options = MTL::CompileOptions::alloc()->init();
  options->setMathMode(MTL::MathModeSafe);
  MTL::Library* library = device->newLibrary(source, options, error);
  MTL::CompileOptions* configured = MTL::CompileOptions::alloc()->init();
  Configure(configured);
  device->newLibrary(source, configured, error);
  device->newLibrary(source, SafeOptions(), error);
  return library;
}
