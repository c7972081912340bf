// Shader parameters filled on the render thread, UE 5 style: world positions and matrices are
// double (FVector, FMatrix) and the GPU takes float (FVector3f, FMatrix44f).
#include "ue_mini.h"

void SetActorParameters(FParameters& Parameters, const AActor* Actor, const FViewInfo& View)
{
	Parameters.ActorPosition = FVector3f(Actor->GetActorLocation());
	const FVector Center = Actor->GetRootComponent()->GetComponentLocation();
	Parameters.BoundsOrigin = FVector3f(Center);
	// A point of the actor, taken into the world by the actor's transform: a world position.
	Parameters.BoundsOrigin = FVector3f(Actor->GetActorTransform().TransformPosition(FVector(0, 0, 100)));
}

void SetPrimitiveParameters(FParameters* Parameters, const FPrimitiveSceneProxy& Proxy, const FSceneView* View)
{
	Parameters->LocalToWorld = FMatrix44f(Proxy.GetLocalToWorld());
	Parameters->WorldToClip = FMatrix44f(View->ViewMatrices.GetViewProjectionMatrix());
	Parameters->LightPositionAndRadius = FVector4f(Proxy.GetBounds().Origin, 50.0f);
	Parameters->Height = Proxy.GetBounds().Origin.Z;
}

// No view here: the finding stands, without a rewrite.
void SetWithoutView(FParameters& Parameters, const USceneComponent& Component)
{
	FVector3f Position(Component.GetComponentTransform().GetTranslation());
	Parameters.ActorPosition = Position;
}

// Already right: camera-relative in double, then narrowed.
void SetTranslated(FParameters& Parameters, const AActor* Actor, const FViewInfo& View)
{
	const FVector Location = Actor->GetActorLocation();
	Parameters.ActorPosition = FVector3f(Location + View.ViewMatrices.GetPreViewTranslation());
	Parameters.BoundsOrigin = FVector3f(Location - View.ViewMatrices.GetViewOrigin());
	Parameters.WorldToClip = FMatrix44f(View.ViewMatrices.GetTranslatedViewProjectionMatrix());
	Parameters.LocalToWorld = FMatrix44f(FMatrix().ConcatTranslation(View.ViewMatrices.GetPreViewTranslation()));
}

// Not world space: a direction, a local value, a point in the actor's own frame, and a float
// that stays on the CPU.
void SetOthers(FParameters& Parameters, const FVector& WindDirection, const AActor* Actor, const FVector& ViewLocation)
{
	Parameters.WindDirection = FVector3f(WindDirection);
	const FVector LocalOffset(0, 0, 100);
	Parameters.BoundsOrigin = FVector3f(LocalOffset);
	// The eye taken into the actor's frame: local, whatever its name says.
	const FVector EyePosition = Actor->GetActorTransform().InverseTransformPosition(ViewLocation);
	Parameters.BoundsOrigin = FVector3f(EyePosition);
	FVector3f ForTheLog(Actor->GetActorLocation());
	(void)ForTheLog;
}

// UE's matrices act on row vectors, so the left factor acts first. A matrix the tables do not
// know, then the view: it hands the view world positions, so it is a model matrix and the
// product is camera-relative. The other way round, the view acts first and its world translation
// stays in the product.
void SetPlaced(FParameters& Parameters, const FMatrix& Placement, const FMatrix& Projection, const FViewInfo& View)
{
	Parameters.LocalToWorld = FMatrix44f(Placement * View.ViewMatrices.GetViewMatrix());
	Parameters.WorldToClip = FMatrix44f(View.ViewMatrices.GetViewMatrix() * Projection);
}

// Right: two numbers named as a position are a point on the screen.
void SetCursor(FParameters& Parameters, const FVector2D& Position)
{
	Parameters.CursorPosition = FVector2f(Position);
}
