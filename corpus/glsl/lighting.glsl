// Lighting helpers shared by the globe's fragment shaders (included, not compiled alone).

// The sun is so far away that only its direction from the origin matters.
vec3 phong(vec3 normal, vec3 sunPosition, vec3 toEye, vec3 albedo)
{
	vec3 toSun = normalize(sunPosition);
	float diffuse = max(dot(normal, toSun), 0.0);
	float specular = pow(max(dot(reflect(-toSun, normal), toEye), 0.0), 32.0);
	return albedo * diffuse + vec3(specular);
}

// Fog grows with the distance from the eye to the surface point.
float fogAmount(vec3 eye, vec3 surfacePoint, float density)
{
	return 1.0 - exp(-density * distance(eye, surfacePoint));
}
