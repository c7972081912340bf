// Direction transforms only: w = 0, 3x3 casts and rotation matrices never hold positions.
cbuffer PerObject : register(b0)
{
	float4x4 LocalToTranslatedWorld;
	float3x3 NormalMatrix;
};

struct VSIn { float3 Normal : NORMAL; float4 Tangent : TANGENT; };

float3x3 BuildTangentBasis(VSIn input)
{
	float3 N = normalize(mul(input.Normal, NormalMatrix));
	float3 T = normalize(mul(float4(input.Tangent.xyz, 0), LocalToTranslatedWorld).xyz);
	float3 B = cross(N, T) * input.Tangent.w;
	return float3x3(T, B, N);
}

float3 ReflectView(float3 ViewDir, VSIn input)
{
	float3x3 Rotation = (float3x3)LocalToTranslatedWorld;
	float3 WorldNormal = mul(input.Normal, Rotation);
	return reflect(ViewDir, normalize(WorldNormal));
}
