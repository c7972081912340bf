// Objective-C forms: a world position read from an object's property, and a struct handed to the
// GPU by a Metal encoder's message (a few declarations stand in for Foundation's and Metal's).
#include "simd_mini.h"

typedef unsigned long NSUInteger;

__attribute__((objc_root_class))
@interface NSObject
@end

@interface Sun : NSObject
@property (nonatomic) simd_double3 position;
@property (nonatomic) simd_double3 direction;
@end

@protocol MTLRenderCommandEncoder
- (void)setFragmentBytes:(const void*)bytes length:(NSUInteger)length atIndex:(NSUInteger)index;
@end

struct SunLight {
  simd_float3 position;
  simd_float3 direction;
};

void DrawSun(id<MTLRenderCommandEncoder> encoder, Sun* sun)
{
  SunLight light;
  light.position = simd_float(sun.position);
  // Right: a direction.
  light.direction = simd_float(sun.direction);
  [encoder setFragmentBytes:&light length:sizeof(light) atIndex:0];
}
