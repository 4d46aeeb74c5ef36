// One cell of the judge's square key light (shared/spec/appearance.md,
// studio set), for MaterialX's GLSL renderer (materialx_render.py).
//
// Why: MaterialX's own lights cannot stand for an area light at finite
// distance: its point_light falls off as 1 / (d + 1)^decay_rate and neither
// it nor directional_light has the emitter's cosine. brdf-render splits the
// 1.2 x 1.2 square into 8 x 8 cells (crates/brdf-render/src/area_light.rs);
// each cell here is one light of this kind at the cell centre, `color` the
// radiance times the cell's area, so the light a surface point receives is
// brdf-render's: L_e (A / n) cos_light / |q - p|^2 from l = (q - p) / |q - p|,
// cos_light = max(0, -n_light . l) (the square emits on its front side).
void mx_judge_square_cell(LightData light, vec3 position, out lightshader result)
{
    vec3 d = light.position - position;
    float dist2 = dot(d, d);
    result.direction = d / sqrt(dist2);
    float cosLight = max(0.0, -dot(light.facing, result.direction));
    result.intensity = light.color * (cosLight / dist2);
}
