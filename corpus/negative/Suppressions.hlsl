// Suppression comments: one used on its line, one above, one for the file, and one stale.
// lwcport-ignore-file: lwc-hack-marker

cbuffer Legacy : register(b0)
{
	float4x4 World; // lwcport-ignore: lwc-uniform-world-float
	// lwcport-ignore: lwc-uniform-world-float
	float3 CameraPosition;
};

float3 Marker(float3 P)
{
	// lwcport-ignore: lwc-float-world-position
	float3 Local = P * 2;
	return Local + LWCHackToFloat(PrimaryView.PreViewTranslation);
}
