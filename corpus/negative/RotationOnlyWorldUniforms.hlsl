// A lighting pass whose host uploads only the rotation and scale of each transform, as 3x3
// matrices named like the full ones. A 3x3 matrix holds no translation, so nothing here is an
// absolute world value, whatever the names say.
cbuffer PerObject
{
	float3x3 World;
	float3x3 LocalToWorld;
	float3 LightDirection;
};

struct VSOut
{
	float4 Position : SV_Position;
	float3 Normal : NORMAL;
};

VSOut MainVS(float4 ClipPosition : POSITION, float3 Normal : NORMAL, float3 Tangent : TANGENT)
{
	VSOut o;
	o.Position = ClipPosition;
	o.Normal = normalize(mul(Normal, LocalToWorld) + mul(Tangent, World) * 0.0);
	return o;
}

float4 MainPS(VSOut i) : SV_Target
{
	return float4(saturate(dot(normalize(i.Normal), -LightDirection)).xxx, 1);
}
