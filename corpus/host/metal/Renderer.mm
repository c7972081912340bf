// An Objective-C++ renderer's Metal set-up (a few declarations stand in for Foundation's and
// Metal's headers) that compiles shaders doing DoubleFloat arithmetic.
typedef signed char BOOL;
#define YES ((BOOL)1)
#define NO ((BOOL)0)
#define nil nullptr

__attribute__((objc_root_class))
@interface NSObject
+ (instancetype)alloc;
+ (instancetype)new;
- (instancetype)init;
@end

@class NSString;
@class NSError;
typedef long NSInteger;
typedef enum : NSInteger { MTLMathModeSafe = 0, MTLMathModeRelaxed = 1, MTLMathModeFast = 2 } MTLMathMode;

@interface MTLCompileOptions : NSObject
@property (nonatomic) BOOL fastMathEnabled;
@property (nonatomic) MTLMathMode mathMode;
@property (nonatomic) NSInteger languageVersion;
@end

@protocol MTLLibrary
@end

@protocol MTLDevice
- (id<MTLLibrary>)newLibraryWithSource:(NSString*)source options:(MTLCompileOptions*)options error:(NSError**)error;
@end

void RememberOptions(MTLCompileOptions* options);

// Fast math turned on, by a property and by a message; relaxed math reassociates as well.
void Configure(MTLCompileOptions* terrain, MTLCompileOptions* sky, MTLCompileOptions* water)
{
  terrain.fastMathEnabled = YES;
  [sky setMathMode:MTLMathModeRelaxed];
  water.mathMode = MTLMathModeFast;
}

// Right: safe math, set either way.
void ConfigureSafe(MTLCompileOptions* terrain, MTLCompileOptions* sky)
{
  terrain.mathMode = MTLMathModeSafe;
  [sky setFastMathEnabled:NO];
}

id<MTLLibrary> BuildLibraries(id<MTLDevice> device, NSString* source, NSError** error)
{
  // No options: Metal's default, fast math.
  [device newLibraryWithSource:source options:nil error:error];
  // Options made here and left at the default.
  MTLCompileOptions* options = [[MTLCompileOptions alloc] init];
  options.languageVersion = 3;
  [device newLibraryWithSource:source options:options error:error];
  // Options made safe before the compile.
  MTLCompileOptions* safe = [MTLCompileOptions new];
  safe.mathMode = MTLMathModeSafe;
  [device newLibraryWithSource:source options:safe error:error];
  // Options handed to other code, which may set them: not judged.
  MTLCompileOptions* shared = [MTLCompileOptions new];
  RememberOptions(shared);
  return [device newLibraryWithSource:source options:shared error:error];
}
