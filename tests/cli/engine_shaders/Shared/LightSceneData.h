// Test engine: a struct the generated Scene uniform buffer holds a buffer of.
#pragma once
struct FLightSceneData
{
	float3 TranslatedWorldPosition;
	float InvRadius;
};
