// Compute-shader particle update: positions kept in a structured buffer in world space.
struct Particle
{
	float3 WorldPosition;
	float3 Velocity;
	float Age;
};

RWStructuredBuffer<Particle> Particles : register(u0);

cbuffer SimParams : register(b0)
{
	float3 EmitterPosition;
	float DeltaTime;
	float3 Gravity;
	float MaxAge;
};

[numthreads(64, 1, 1)]
void UpdateCS(uint3 Id : SV_DispatchThreadID)
{
	Particle p = Particles[Id.x];
	p.Velocity += Gravity * DeltaTime;
	p.WorldPosition += p.Velocity * DeltaTime;
	p.Age += DeltaTime;
	[flatten] if (p.Age > MaxAge)
	{
		p.WorldPosition = EmitterPosition;
		p.Age = 0;
	}
	Particles[Id.x] = p;
}
