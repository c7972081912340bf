// A few Unreal-like declarations, written for lwcport's corpus: just enough of UE 5's math
// types, views and shader-parameter macros for the host corpus to compile. Not Unreal's code.
#pragma once

namespace UE::Math {
template <typename T>
struct TVector {
  T X = 0, Y = 0, Z = 0;
  TVector() = default;
  TVector(T InX, T InY, T InZ) : X(InX), Y(InY), Z(InZ) {}
  // As in UE 5: converting between precisions is explicit.
  template <typename U>
  explicit TVector(const TVector<U>& V) : X(T(V.X)), Y(T(V.Y)), Z(T(V.Z)) {}
  TVector operator+(const TVector& V) const { return {X + V.X, Y + V.Y, Z + V.Z}; }
  TVector operator-(const TVector& V) const { return {X - V.X, Y - V.Y, Z - V.Z}; }
  TVector operator-() const { return {-X, -Y, -Z}; }
  TVector operator*(T Scale) const { return {X * Scale, Y * Scale, Z * Scale}; }
};

template <typename T>
struct TVector4 {
  T X = 0, Y = 0, Z = 0, W = 0;
  TVector4() = default;
  TVector4(const TVector<T>& V, T InW) : X(V.X), Y(V.Y), Z(V.Z), W(InW) {}
  template <typename U>
  explicit TVector4(const TVector<U>& V, T InW = 1) : X(T(V.X)), Y(T(V.Y)), Z(T(V.Z)), W(InW) {}
};

template <typename T>
struct TMatrix {
  T M[4][4] = {};
  TMatrix() = default;
  template <typename U>
  explicit TMatrix(const TMatrix<U>& Other) {
    for (int R = 0; R < 4; ++R)
      for (int C = 0; C < 4; ++C) M[R][C] = T(Other.M[R][C]);
  }
  TMatrix operator*(const TMatrix& Other) const { return Other; }
  TMatrix ConcatTranslation(const TVector<T>& Translation) const {
    TMatrix Result = *this;
    Result.M[3][0] += Translation.X;
    Result.M[3][1] += Translation.Y;
    Result.M[3][2] += Translation.Z;
    return Result;
  }
  TVector<T> GetOrigin() const { return {M[3][0], M[3][1], M[3][2]}; }
  TMatrix Inverse() const { return *this; }
};

template <typename T>
struct TTranslationMatrix : TMatrix<T> {
  explicit TTranslationMatrix(const TVector<T>& Delta) { this->M[3][0] = Delta.X, this->M[3][1] = Delta.Y, this->M[3][2] = Delta.Z; }
};

template <typename T>
struct TTransform {
  TVector<T> Translation;
  TVector<T> GetTranslation() const { return Translation; }
  TVector<T> GetLocation() const { return Translation; }
  TVector<T> TransformPosition(const TVector<T>& V) const { return V + Translation; }
  TVector<T> InverseTransformPosition(const TVector<T>& V) const { return V - Translation; }
  TMatrix<T> ToMatrixWithScale() const { return {}; }
};

// As in UE 5: the two numbers are X and Y, and also XY[2], in a union.
template <typename T>
struct TVector2 {
  union {
    struct {
      T X, Y;
    };
    T XY[2];
  };
  TVector2() : X(0), Y(0) {}
  template <typename U>
  explicit TVector2(const TVector2<U>& V) : X(T(V.X)), Y(T(V.Y)) {}
};

template <typename T>
struct TBoxSphereBounds {
  TVector<T> Origin, BoxExtent;
  T SphereRadius = 0;
};
}  // namespace UE::Math

using FVector = UE::Math::TVector<double>;
using FVector3d = UE::Math::TVector<double>;
using FVector3f = UE::Math::TVector<float>;
using FVector2D = UE::Math::TVector2<double>;
using FVector2f = UE::Math::TVector2<float>;
using FVector4 = UE::Math::TVector4<double>;
using FVector4f = UE::Math::TVector4<float>;
using FMatrix = UE::Math::TMatrix<double>;
using FMatrix44d = UE::Math::TMatrix<double>;
using FMatrix44f = UE::Math::TMatrix<float>;
using FTranslationMatrix = UE::Math::TTranslationMatrix<double>;
using FTransform = UE::Math::TTransform<double>;
using FBoxSphereBounds = UE::Math::TBoxSphereBounds<double>;

// UE 5.4's DoubleFloat host types (Math/DoubleFloat.h): a value as the float nearest it (High)
// and the float nearest the rest (Low); a matrix as a float matrix relative to a float origin.
struct FDFScalar {
  FDFScalar() = default;
  FDFScalar(double Value) : High(static_cast<float>(Value)), Low(static_cast<float>(Value - static_cast<double>(High))) {}
  float High = 0;
  float Low = 0;
};

struct FDFVector3 {
  FDFVector3() = default;
  template <typename T>
  FDFVector3(const UE::Math::TVector<T>& Value) {
    const FDFScalar X(Value.X), Y(Value.Y), Z(Value.Z);
    High = FVector3f(X.High, Y.High, Z.High);
    Low = FVector3f(X.Low, Y.Low, Z.Low);
  }
  FVector3f High, Low;
};

struct FDFMatrix {
  FMatrix44f M;
  FVector3f PostTranslation;  // added after M: world = local * M + PostTranslation
  static FDFMatrix MakeToRelativeWorldMatrix(const FVector3f Origin, const FMatrix& ToWorld) {
    FDFMatrix Result;
    Result.M = FMatrix44f(ToWorld.ConcatTranslation(-FVector(Origin)));
    Result.PostTranslation = Origin;
    return Result;
  }
};

struct USceneComponent {
  FVector GetComponentLocation() const { return {}; }
  const FTransform& GetComponentTransform() const { return Transform; }
  FTransform Transform;
};

struct AActor {
  FVector GetActorLocation() const { return {}; }
  FTransform GetActorTransform() const { return {}; }
  USceneComponent* GetRootComponent() const { return nullptr; }
};

struct FViewMatrices {
  const FVector& GetPreViewTranslation() const { return PreViewTranslation; }
  const FVector& GetViewOrigin() const { return ViewOrigin; }
  const FMatrix& GetViewProjectionMatrix() const { return ViewProjection; }
  const FMatrix& GetTranslatedViewProjectionMatrix() const { return TranslatedViewProjection; }
  const FMatrix& GetViewMatrix() const { return View; }
  FVector PreViewTranslation, ViewOrigin;
  FMatrix ViewProjection, TranslatedViewProjection, View;
};

struct FSceneView {
  FViewMatrices ViewMatrices;
};
struct FViewInfo : FSceneView {};

struct FPrimitiveSceneProxy {
  const FMatrix& GetLocalToWorld() const { return LocalToWorld; }
  const FBoxSphereBounds& GetBounds() const { return Bounds; }
  FMatrix LocalToWorld;
  FBoxSphereBounds Bounds;
};

// Shader parameter structs, as UE's macros declare them (their members are what the GPU reads).
#define BEGIN_SHADER_PARAMETER_STRUCT(Name, Api) struct Name {
#define SHADER_PARAMETER(Type, Name) Type Name;
#define SHADER_PARAMETER_ARRAY(Type, Name, Count) Type Name Count;
#define END_SHADER_PARAMETER_STRUCT() };

BEGIN_SHADER_PARAMETER_STRUCT(FParameters, )
  SHADER_PARAMETER(FVector3f, ActorPosition)
  SHADER_PARAMETER(FVector4f, LightPositionAndRadius)
  SHADER_PARAMETER(FMatrix44f, LocalToWorld)
  SHADER_PARAMETER(FMatrix44f, WorldToClip)
  SHADER_PARAMETER(FVector3f, BoundsOrigin)
  SHADER_PARAMETER(FVector3f, WindDirection)
  SHADER_PARAMETER(float, Height)
  SHADER_PARAMETER(FVector2f, CursorPosition)
END_SHADER_PARAMETER_STRUCT()
