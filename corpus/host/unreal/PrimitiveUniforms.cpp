// Per-primitive shader parameters in a UE 5.4 unit (it declares the DoubleFloat types), filled
// where no view is at hand: scene data must not depend on the camera, so these take high/low pairs.
#include "ue_mini.h"

BEGIN_SHADER_PARAMETER_STRUCT(FPrimitiveParameters, )
	SHADER_PARAMETER(FVector3f, ObjectOrigin)
	SHADER_PARAMETER(float, ObjectHeight)
	SHADER_PARAMETER(FMatrix44f, LocalToWorld)
	SHADER_PARAMETER(FMatrix44f, WorldToClip)
	SHADER_PARAMETER(FVector3f, PivotPosition)
	SHADER_PARAMETER(FVector3f, PivotPositionLow)
	SHADER_PARAMETER(FVector4f, OriginAndRadius)
END_SHADER_PARAMETER_STRUCT()

void SetPrimitiveParameters(FPrimitiveParameters& Parameters, const FPrimitiveSceneProxy& Proxy)
{
	Parameters.ObjectOrigin = FVector3f(Proxy.GetBounds().Origin);
	Parameters.ObjectHeight = Proxy.GetBounds().Origin.Z;
}

void SetPrimitiveTransform(FPrimitiveParameters* Parameters, const FPrimitiveSceneProxy& Proxy, const FMatrix& WorldToClip)
{
	Parameters->LocalToWorld = FMatrix44f(Proxy.GetLocalToWorld());
	// A matrix from world space needs the camera as its origin: no rewrite here.
	Parameters->WorldToClip = FMatrix44f(WorldToClip);
	// Packed with the radius: split by hand.
	Parameters->OriginAndRadius = FVector4f(Proxy.GetBounds().Origin, 100.0f);
}

// Already right: the high half and the low half, both written here.
void SetPivot(FPrimitiveParameters& Parameters, const AActor* Actor)
{
	const FVector Pivot = Actor->GetActorLocation();
	Parameters.PivotPosition = FVector3f(Pivot);
	Parameters.PivotPositionLow = FVector3f(Pivot - FVector(Parameters.PivotPosition));
}

FPrimitiveParameters* AllocateParameters();

// The object is a call, which the rewrite would make twice: no rewrite.
void SetFromAllocation(const FPrimitiveSceneProxy& Proxy)
{
	AllocateParameters()->ObjectOrigin = FVector3f(Proxy.GetBounds().Origin);
}

// The struct is declared in ue_mini.h, which stands for an engine header outside the project: no high/low rewrite.
void SetSharedParameters(FParameters& Parameters, const AActor* Actor)
{
	Parameters.ActorPosition = FVector3f(Actor->GetActorLocation());
}
