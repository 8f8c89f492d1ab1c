// `colors: array<vec3<f32>, 2>` has a stride of 16 bytes: its Rust field is an array of
// `Vec3F32Stride16`, and three bare floats per element (a stride of 12) do not fit it.
use bindings_compile_fail::keys::structs::Light;

fn main() {
    let mut light: Light = bytemuck::Zeroable::zeroed();
    light.colors = [[1.0, 0.5, 0.25]; 2];
    let _ = light;
}
