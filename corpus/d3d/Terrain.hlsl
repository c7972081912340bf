// D3D-style terrain: heights sampled by world-space XZ, which drifts far from the origin.
Texture2D gHeightMap : register(t0);
SamplerState gLinear : register(s0);

cbuffer TerrainConstants : register(b0)
{
	row_major float4x4 World;
	row_major float4x4 ViewProj;
	float3 CameraPosition;
	float TexelSize;
};

struct VSIn { float3 Pos : POSITION; float2 UV : TEXCOORD0; };
struct VSOut { float4 Pos : SV_Position; float2 UV : TEXCOORD0; float Fog : TEXCOORD1; };

float SampleHeight(float2 WorldXZ)
{
	return gHeightMap.SampleLevel(gLinear, WorldXZ * TexelSize, 0).r;
}

VSOut TerrainVS(VSIn input)
{
	VSOut output;
	float4 worldPos = mul(float4(input.Pos, 1), World);
	worldPos.y += SampleHeight(worldPos.xz);
	output.Pos = mul(worldPos, ViewProj);
	output.UV = input.UV;
	output.Fog = saturate(distance(worldPos.xyz, CameraPosition) / 100000.0f);
	return output;
}
