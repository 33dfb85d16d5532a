/* The surface model's device data, shared by host and kernels (model: kernels/common/brdf.h and
 * src/shading/brdf.h).
 *
 * Gloss code: one float per surface holding an integer below 2^17 (exact in float), carried by
 * Material.emission.w, Sphere.emission.w and the GBuffer's emission.w:
 *   code = roughness_q + 256 * f0_q + 65536 * metal
 *   roughness = roughness_q / 255, f0 = f0_q / RP_GLOSS_F0_SCALE (dielectric, 0 .. 0.249 in
 *   steps of 0.001: real dielectrics lie in 0.02 .. 0.17), metal = 1: F0 is the albedo colour
 *   and there is no diffuse base (f0_q unused). code 0 (f0 = 0, not metal): no coat, plain
 *   Lambert (the walls, the background, fireballs and particles).
 *
 * Table: N^2 float4 (N = RP_BRDF_TABLE_SIZE), row j = roughness j / (N - 1) (nodes: 0 and 1
 * exact), column i = mu (the cosine of the view or light direction) (i + 0.5) / N (cell
 * centres), entry (E(mu), S(mu), E_avg, S_avg) of that roughness (src/shading/brdf_tables.h
 * integrates them at start-up). Lookups are bilinear, clamped at the edges. 16 KiB.
 */
#ifndef ROLYPOLY_SHARED_BRDF_LAYOUT_H
#define ROLYPOLY_SHARED_BRDF_LAYOUT_H

#define RP_BRDF_TABLE_SIZE 32
#define RP_GLOSS_F0_SCALE 1024.0f
#define RP_GLOSS_METAL 65536

#endif
