// The tissue layer of the jellyfish materials: the fragment shader shared by CPU meshes
// (`TissueMaterial`) and templates (`SurfaceMaterial`). It is Bevy's PBR fragment with
// one change before lighting: the opacity follows the optical path through the tissue
// (Beer–Lambert), and the glow layer adds the glow band.
//
// `uv_b` carries each vertex's tissue (`shape::tissue`): x, the thickness relative to the
// reference the material's painted opacity is for (the mesoglea at the apex, a tube at
// its root); y, the glow band's share. A shell (a bell's sheet) is crossed on a path of
// thickness / |N·V|, so rims read milky and the centre clear; a solid tube on a chord of
// thickness × |N·V|, so its edges fade.

#import bevy_pbr::{
    pbr_types,
    pbr_functions::alpha_discard,
    pbr_fragment::pbr_input_from_standard_material,
    forward_io::{VertexOutput, FragmentOutput},
    pbr_functions::{apply_pbr_lighting, main_pass_post_lighting_processing},
    pbr_types::STANDARD_MATERIAL_FLAGS_UNLIT_BIT,
}
#ifdef OIT_ENABLED
#import bevy_core_pipeline::oit::oit_draw
#endif

const SHELL: u32 = 0u;
const SOLID: u32 = 1u;

struct Tissue {
    // SHELL, SOLID, or any other value: opacity as painted (the glow layer).
    kind: u32,
    // The glow band's radiance at full share, linear RGB.
    band: vec4<f32>,
};

@group(#{MATERIAL_BIND_GROUP}) @binding(102) var<uniform> tissue: Tissue;

// Grazing views are capped at twenty times the straight-on path.
const GRAZING: f32 = 0.05;

// The painted opacity `a` is for the reference path; `path` is this one's multiple of it.
fn beer_lambert(a: f32, path: f32) -> f32 {
    let depth = -log(max(1.0 - a, 1e-4)) * path;
    return 1.0 - exp(-depth);
}

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
#ifdef VERTEX_UVS_B
    let thickness = in.uv_b.x;
    let band = in.uv_b.y;
#else
    let thickness = 1.0;
    let band = 0.0;
#endif
    let facing = max(abs(dot(normalize(pbr_input.world_normal), pbr_input.V)), GRAZING);
    let a = pbr_input.material.base_color.a;
    if tissue.kind == SHELL {
        pbr_input.material.base_color.a = beer_lambert(a, thickness / facing);
    } else if tissue.kind == SOLID {
        pbr_input.material.base_color.a = beer_lambert(a, thickness * facing);
    }
    pbr_input.material.base_color = alpha_discard(pbr_input.material, pbr_input.material.base_color);

    var out: FragmentOutput;
    if (pbr_input.material.flags & STANDARD_MATERIAL_FLAGS_UNLIT_BIT) == 0u {
        out.color = apply_pbr_lighting(pbr_input);
    } else {
        out.color = pbr_input.material.base_color;
    }
    out.color = vec4(out.color.rgb + tissue.band.rgb * band, out.color.a);
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);

#ifdef OIT_ENABLED
    let alpha_mode = pbr_input.material.flags & pbr_types::STANDARD_MATERIAL_FLAGS_ALPHA_MODE_RESERVED_BITS;
    if alpha_mode != pbr_types::STANDARD_MATERIAL_FLAGS_ALPHA_MODE_OPAQUE {
        oit_draw(in.position, out.color);
        discard;
    }
#endif
    return out;
}
