// Engines group their per-frame constants in structs held in one constant buffer. A member is
// uniform data as much as a loose uniform is: the camera position in `Frame.CameraPos` is an
// absolute world position in float32, and a point built from it is one too. A matrix member
// counts only by what the code does with it (hosts that keep objects camera-relative still call
// theirs `World`), so `Frame.World` alone says nothing.
struct FrameData
{
	float4x4 World;
	float3 CameraPos;
	float PlanetRadius;
};

cbuffer FrameConstants : register(b0)
{
	FrameData Frame;
};

float4 SkyPS(float3 ViewRay : TEXCOORD0) : SV_Target
{
	float3 RayStart = Frame.CameraPos + normalize(ViewRay) * 100.0f;
	float Altitude = length(RayStart) - Frame.PlanetRadius;
	return float4(saturate(Altitude / 8000.0f).xxx, 1);
}
