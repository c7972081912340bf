// A deferred pass that rebuilds each pixel's world position from depth with the inverse
// view-projection, then measures its distance to the camera: both uniforms hold absolute world
// data in float32 (the inverse's translation is the camera's position), so the point and the
// distance jitter far from the origin. Engines name these matrices their own way; the common
// spellings count (InvViewProjection, InvViewMatrix, ViewProjectionMatrix, ViewPos).
cbuffer ViewConstants : register(b0)
{
	float4x4 InvViewProjection;
	float4x4 ViewProjectionMatrix;
	float3 ViewPos;
	float FogDensity;
};

Texture2D<float> SceneDepth : register(t0);

float4 FogPS(float4 SvPosition : SV_Position, float2 ScreenUV : TEXCOORD0) : SV_Target
{
	float Depth = SceneDepth.Load(int3(SvPosition.xy, 0));
	float4 Clip = float4(ScreenUV * float2(2, -2) + float2(-1, 1), Depth, 1);
	float4 World = mul(Clip, InvViewProjection);
	float3 WorldPos = World.xyz / World.w;
	float Distance = length(WorldPos - ViewPos);
	return float4(1 - exp(-FogDensity * Distance), 0, 0, 1);
}
