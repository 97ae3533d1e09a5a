// Playback's pose is captured before rasterization (deform.vert): nothing is drawn.
void main() {}
