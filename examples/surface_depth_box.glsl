// An example surface filter: the mean eye depth over a box of one projected particle radius,
// taken over the pixels of the same body, with the normals then rebuilt from the new depth
// (set realtime.surface.shader_normals = true). A starting point, not a method to use: a box
// flattens the surface's real curvature along with the particles' bumps.
void filterSurface(ivec2 pixel, inout SurfaceSample s) {
    int r = int(ceil(s.radiusPx));
    float sum = 0.0, count = 0.0;
    for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (bodyAt(q) != s.body) continue;
            sum += depthAt(q);
            count += 1.0;
        }
    s.depth = sum / count;
}
