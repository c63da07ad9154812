// A surface filter that changes nothing: `realtime.surface.shader = "surface_pass_through.glsl"`
// renders the same image as `realtime.surface.method = "none"`, bit for bit. Start a filter of
// your own from here; realtime/shaders/user_surface.frag lists what it may read.
void filterSurface(ivec2 pixel, inout SurfaceSample s) {}
