// D3D11-style forward lighting with per-object world matrix and eye position constants.
cbuffer cbPerObject : register(b0)
{
	float4x4 gWorld;
	float4x4 gWorldInvTranspose;
	float4x4 gWorldViewProj;
};

cbuffer cbPerFrame : register(b1)
{
	float3 gEyePosW;
	float gFogStart;
	float gFogRange;
	float4 gFogColor;
};

struct VertexIn
{
	float3 PosL : POSITION;
	float3 NormalL : NORMAL;
};

struct VertexOut
{
	float4 PosH : SV_POSITION;
	float3 PosW : POSITION;
	float3 NormalW : NORMAL;
};

VertexOut VS(VertexIn vin)
{
	VertexOut vout;
	vout.PosW = mul(float4(vin.PosL, 1.0f), gWorld).xyz;
	vout.NormalW = mul(vin.NormalL, (float3x3)gWorldInvTranspose);
	vout.PosH = mul(float4(vin.PosL, 1.0f), gWorldViewProj);
	return vout;
}

float4 PS(VertexOut pin) : SV_Target
{
	pin.NormalW = normalize(pin.NormalW);
	float3 toEye = gEyePosW - pin.PosW;
	float distToEye = length(toEye);
	toEye /= distToEye;
	float fogLerp = saturate((distToEye - gFogStart) / gFogRange);
	float4 litColor = float4(pin.NormalW * 0.5f + 0.5f, 1.0f);
	litColor = lerp(litColor, gFogColor, fogLerp);
	return litColor;
}
