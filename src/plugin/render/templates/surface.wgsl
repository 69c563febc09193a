// The jellyfish surface built on the GPU from a template mesh and a packed shape block.
//
// A template mesh (one per resolution) carries only topology and UVs; each instance's
// `MeshTag` picks its shape block (tag >> 1) and its part (tag & 1: 0 the umbrella, 1 the
// tentacles), and this shader turns the vertex's index into its position and normal. A
// block is the individual's own words, whose `H_FRAME` says where the rest is: in the
// block itself, or (a far jellyfish) its recorded step's frame in `recorded`. A
// CPU mesh wearing the same material (tag CPU_MESH_TAG) is drawn as it is. It
// mirrors `shape::packed` (`umbrella_vertex`, `tentacle_vertex`) and `shape::perlin` line
// for line: change one, change the other (the Rust mirror is tested against the CPU mesh).
// Its constants, `packed::*` (the block's layout and what the arithmetic shares with the
// CPU mesh), are imported from the module the plugin writes from `shape::packed::layout`'s
// table: none is copied here. The same file serves the forward and the prepass/shadow
// pipelines (PREPASS_PIPELINE); a test composes and validates both without a GPU.

#import bevy_pbr::{
    mesh_bindings::mesh,
    mesh_functions,
    view_transformations::position_world_to_clip,
}
#import bevy_jellyfish::packed
#ifdef PREPASS_PIPELINE
#import bevy_pbr::prepass_io::VertexOutput
#else
#import bevy_pbr::forward_io::VertexOutput
#endif

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<storage, read> offsets: array<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var<storage, read> shapes: array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var<storage, read> recorded: array<f32>;

// The vertex's block (packed::Block): where the individual's words start in `shapes`, and
// whether its frame is in `recorded` (a far jellyfish's recorded step) or in `shapes`.
// Every function's `base` is where the frame starts in that buffer.
var<private> individual_at: u32;
var<private> frame_is_recorded: bool;
// The trails' nodes per guide (packed::H_TRAIL_NODES) and values per guide.
var<private> trail_nodes: u32;
var<private> trail_stride: u32;

// A value of the frame (packed::Block::value).
fn frame_value(at: u32) -> f32 {
    if frame_is_recorded {
        return recorded[at];
    }
    return shapes[at];
}

// One of the individual's own words (packed::Block::individual).
fn individual(at: u32) -> f32 {
    return shapes[individual_at + at];
}

// A template's own attributes are its rest shape, which only CPU meshes (tagged
// packed::CPU_MESH_TAG) draw; the locations are those of bevy_pbr's forward_io and
// prepass_io.
struct Vertex {
    @builtin(instance_index) instance_index: u32,
    @builtin(vertex_index) index: u32,
    @location(0) position: vec3<f32>,
#ifdef PREPASS_PIPELINE
#ifdef VERTEX_UVS_A
    @location(1) uv: vec2<f32>,
#endif
#ifdef VERTEX_UVS_B
    @location(2) uv_b: vec2<f32>,
#endif
#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
#ifdef VERTEX_NORMALS
    @location(3) normal: vec3<f32>,
#endif
#endif
#else
#ifdef VERTEX_NORMALS
    @location(1) normal: vec3<f32>,
#endif
#ifdef VERTEX_UVS_A
    @location(2) uv: vec2<f32>,
#endif
#ifdef VERTEX_UVS_B
    @location(3) uv_b: vec2<f32>,
#endif
#endif
};

// A CPU mesh's vertex as it is.
fn cpu_vertex(vertex: Vertex) -> Surface {
    var out = Surface(vertex.position, vec3(0.0, 1.0, 0.0), vec2(1.0, 0.0));
#ifdef PREPASS_PIPELINE
#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
#ifdef VERTEX_NORMALS
    out.normal = vertex.normal;
#endif
#endif
#else
#ifdef VERTEX_NORMALS
    out.normal = vertex.normal;
#endif
#endif
#ifdef VERTEX_UVS_B
    out.tissue = vertex.uv_b;
#endif
    return out;
}

struct Surface {
    position: vec3<f32>,
    normal: vec3<f32>,
    // shape::tissue: relative thickness, glow band.
    tissue: vec2<f32>,
};

struct Disc {
    centre: vec3<f32>,
    radius: f32,
    radial: vec2<f32>,
};

// ---- shape::perlin ----

fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn lattice_hash(seed: u32, corner: vec4<i32>) -> u32 {
    var h = pcg(seed ^ 0x9E3779B9u);
    h = pcg(h ^ bitcast<u32>(corner.x));
    h = pcg(h ^ bitcast<u32>(corner.y));
    h = pcg(h ^ bitcast<u32>(corner.z));
    h = pcg(h ^ bitcast<u32>(corner.w));
    return h;
}

fn gradient(h: u32, d_in: vec4<f32>) -> f32 {
    var d = d_in;
    let zero = (h >> 3u) & 3u;
    var sum = 0.0;
    var sign_bit = 0u;
    for (var i = 0u; i < 4u; i++) {
        if i == zero {
            continue;
        }
        if ((h >> sign_bit) & 1u) == 1u {
            sum -= d[i];
        } else {
            sum += d[i];
        }
        sign_bit += 1u;
    }
    return sum;
}

fn fade(t: vec4<f32>) -> vec4<f32> {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn perlin4(seed: u32, p: vec4<f32>) -> f32 {
    let cell = floor(p);
    let corner = vec4<i32>(cell);
    let d = p - cell;
    var f = fade(d);
    var sum = 0.0;
    for (var c = 0u; c < 16u; c++) {
        var lattice = corner;
        var offset = d;
        var weight = 1.0;
        for (var i = 0u; i < 4u; i++) {
            if ((c >> i) & 1u) == 1u {
                lattice[i] += 1;
                offset[i] -= 1.0;
                weight *= f[i];
            } else {
                weight *= 1.0 - f[i];
            }
        }
        sum += weight * gradient(lattice_hash(seed, lattice), offset);
    }
    return clamp(sum, -1.0, 1.0);
}

// ---- shape::discs ----

fn read_disc(at: u32) -> Disc {
    return Disc(
        vec3(frame_value(at), frame_value(at + 1u), 0.0),
        frame_value(at + 2u),
        vec2(frame_value(at + 3u), frame_value(at + 4u)),
    );
}

fn perp(v: vec2<f32>) -> vec2<f32> {
    return vec2(-v.y, v.x);
}

fn normalize_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    if length_squared > 0.0 {
        return v * inverseSqrt(length_squared);
    }
    return fallback;
}

fn disc_axis(d: Disc) -> vec3<f32> {
    return vec3(perp(d.radial), 0.0);
}

fn disc_direction(d: Disc, cs: vec2<f32>) -> vec3<f32> {
    return vec3(d.radial.x * cs.x, d.radial.y * cs.x, cs.y);
}

fn disc_point(d: Disc, cs: vec2<f32>) -> vec3<f32> {
    return d.centre + d.radius * disc_direction(d, cs);
}

// The left and right slice normals at `at` swept to angle σ = (cos, sin).
fn disc_normal(d: Disc, at: u32, cs: vec2<f32>) -> vec3<f32> {
    let left = vec2(frame_value(at), frame_value(at + 1u));
    let right = vec2(frame_value(at + 2u), frame_value(at + 3u));
    let a = perp(d.radial);
    let right_radial = dot(right, d.radial);
    let right_axial = dot(right, a);
    let left_radial = -dot(left, d.radial);
    let left_axial = dot(left, a);
    let w = 0.5 * (1.0 - cs.x);
    let radial = right_radial + (left_radial - right_radial) * w;
    let axial = right_axial + (left_axial - right_axial) * w;
    return normalize_or(radial * disc_direction(d, cs) + axial * disc_axis(d), disc_axis(d));
}

// ---- shape::packed ----

fn count(base: u32, at: u32) -> u32 {
    return bitcast<u32>(frame_value(base + at));
}

fn noise(base: u32, lat: f32, cs: vec2<f32>) -> f32 {
    let r = frame_value(base + packed::H_LON_RADIUS);
    return perlin4(
        bitcast<u32>(individual(packed::H_SEED)),
        vec4(
            frame_value(base + packed::H_LAT_FREQUENCY) * lat,
            r * cs.x,
            r * cs.y,
            individual(packed::H_TAU),
        ),
    );
}

fn lobe(base: u32, sigma: f32) -> f32 {
    var s = sin(frame_value(base + packed::H_STRUCTURAL_FREQUENCY) * sigma);
    if frame_value(base + packed::H_STRUCTURAL_ABS) > 0.5 {
        s = abs(s);
    }
    return frame_value(base + packed::H_STRUCTURAL) * s;
}

fn ripple(base: u32, sigma: f32) -> f32 {
    return frame_value(base + packed::H_COMPRESSION) * 0.5
        * (1.0 + sin(frame_value(base + packed::H_COMPRESSION_FREQUENCY) * sigma));
}

fn apex_fade(latitude: f32) -> f32 {
    let x = clamp(latitude / packed::APEX_FADE, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

fn ring_at(base: u32, k: u32) -> u32 {
    return base + packed::HEADER + k * packed::RING;
}

fn umbrella_point(base: u32, surface: u32, k: u32, j: u32) -> Surface {
    let at = ring_at(base, k);
    let sub = read_disc(at + packed::RING_SUBUMBRELLA);
    let ex = read_disc(at + packed::RING_EXUMBRELLA);
    let latitude = frame_value(at + packed::RING_LATITUDE);
    let contraction = frame_value(at + packed::RING_CONTRACTION);
    var side = 1.0;
    if surface == 1u {
        side = -1.0;
    }
    if k == 0u {
        let n = disc_normal(sub, at + packed::RING_NORMALS, vec2(1.0, 0.0));
        var centre = sub.centre;
        if surface == 0u {
            centre = ex.centre;
        }
        return Surface(centre, n * side, vec2(1.0, 0.0));
    }
    let segments = count(base, packed::H_SEGMENTS);
    let sigma = packed::TAU * f32(j % segments) / f32(segments);
    let cs = vec2(cos(sigma), sin(sigma));
    let n = disc_normal(sub, at + packed::RING_NORMALS, cs);
    let fade = apex_fade(latitude);
    let shared_offset = lobe(base, sigma) * fade
        + individual(packed::H_UNSTRUCTURED) * latitude * noise(base, latitude, cs);
    var position: vec3<f32>;
    if surface == 0u {
        position = disc_point(ex, cs) + n * (shared_offset + ripple(base, sigma) * fade * contraction);
    } else {
        position = disc_point(sub, cs) + n * shared_offset;
    }
    return Surface(position, n * side, vec2(1.0, 0.0));
}

// ---- shape::tissue ----

fn ring_thickness(base: u32, k: u32) -> f32 {
    let at = ring_at(base, k);
    let sub = read_disc(at + packed::RING_SUBUMBRELLA);
    let ex = read_disc(at + packed::RING_EXUMBRELLA);
    return distance(disc_point(ex, vec2(1.0, 0.0)), disc_point(sub, vec2(1.0, 0.0)));
}

fn relative_thickness(thickness: f32, reference: f32) -> f32 {
    if reference > 0.0 {
        return thickness / reference;
    }
    return 1.0;
}

fn band(contraction: f32) -> f32 {
    return 4.0 * contraction * (1.0 - contraction);
}

fn taper(fraction: f32) -> f32 {
    return 1.0 - (1.0 - packed::TENTACLE_TIP) * clamp(fraction, 0.0, 1.0);
}

// packed::ring_tissue.
fn ring_tissue(base: u32, k: u32) -> vec2<f32> {
    return vec2(
        relative_thickness(ring_thickness(base, k), ring_thickness(base, 0u)),
        band(frame_value(ring_at(base, k) + packed::RING_CONTRACTION)),
    );
}

// Sheet ring l (-1 the exumbrellar apex ... 2·rings the subumbrellar apex) at column j.
fn sheet_point(base: u32, l: i32, j: u32) -> vec3<f32> {
    let r = i32(count(base, packed::H_RINGS));
    if l < 0 {
        return umbrella_point(base, 0u, 0u, j).position;
    }
    if l >= 2 * r {
        return umbrella_point(base, 1u, 0u, j).position;
    }
    if l < r {
        return umbrella_point(base, 0u, u32(l + 1), j).position;
    }
    return umbrella_point(base, 1u, u32(2 * r - l), j).position;
}

fn umbrella_vertex(base: u32, index: u32) -> Surface {
    let rings = count(base, packed::H_RINGS);
    let segments = count(base, packed::H_SEGMENTS);
    let surface_len = 1u + rings * (segments + 1u);
    let surface = index / surface_len;
    let r = index % surface_len;
    if r == 0u {
        var apex = umbrella_point(base, surface, 0u, 0u);
        apex.tissue = ring_tissue(base, 0u);
        return apex;
    }
    let k = 1u + (r - 1u) / (segments + 1u);
    let j = (r - 1u) % (segments + 1u);
    let here = umbrella_point(base, surface, k, j);
    var l = i32(k) - 1;
    if surface == 1u {
        l = 2 * i32(rings) - i32(k);
    }
    let around = sheet_point(base, l, j + 1u) - sheet_point(base, l, j + segments - 1u);
    let along = sheet_point(base, l + 1, j) - sheet_point(base, l - 1, j);
    let normal = cross(around, along);
    var out = here;
    if dot(normal, normal) > 0.0 {
        out.normal = normalize(normal);
    }
    out.tissue = ring_tissue(base, k);
    return out;
}

fn tentacle_centre(base: u32, t: u32, m: u32) -> vec3<f32> {
    let count_t = count(base, packed::H_TENTACLES);
    let points = count(base, packed::H_POINTS);
    let sigma = packed::TAU * f32(t) / f32(count_t);
    let cs = vec2(cos(sigma), sin(sigma));
    let aperture = read_disc(base + packed::H_APERTURE);
    let normal = disc_normal(aperture, base + packed::H_MARGIN_NORMALS, cs);
    let sideways = disc_direction(aperture, vec2(-cs.y, cs.x));
    let fraction = f32(m) / f32(points - 1u);
    let lat = 1.0 + fraction;
    let amplitude = individual(packed::H_UNSTRUCTURED);
    let along = lobe(base, sigma) + amplitude * noise(base, lat, cs);
    let side = amplitude * fraction * noise(base, lat + packed::SIDEWAYS, cs);
    // tentacles::along, between the two discs around the drawn length.
    let reach = tentacle_reach(base, t);
    let x = fraction * reach * f32(points - 1u);
    let i = min(u32(x), points - 2u);
    let first = ring_at(base, count(base, packed::H_RINGS) + 1u);
    let p = disc_point(read_disc(first + i * packed::DISC), cs);
    let q = disc_point(read_disc(first + (i + 1u) * packed::DISC), cs);
    let trail = trail_offset(base, sigma, fraction * reach);
    return p + (q - p) * (x - f32(i)) + trail + normal * along + sideways * side;
}

// packed::trail_offset (sim::guides::Trail::at): node m of guide g, the root zero.
fn trail_node(start: u32, g: u32, m: u32) -> vec3<f32> {
    if m == 0u {
        return vec3(0.0);
    }
    let h = 3u * (m - 1u);
    return vec3(trail_half(start, g, h), trail_half(start, g, h + 1u), trail_half(start, g, h + 2u));
}

// Half `h` of guide g's values: two to a value, the first in its low bits.
fn trail_half(start: u32, g: u32, h: u32) -> f32 {
    let pair = bitcast<u32>(shapes[start + g * trail_stride + h / 2u]);
    return half_to_f32((pair >> (16u * (h & 1u))) & 0xffffu);
}

// An IEEE binary16 as an f32, exactly (what `half::f16::to_f32` gives), without the
// float16 capability `unpack2x16float` needs. The trail holds no infinities or NaNs.
fn half_to_f32(bits: u32) -> f32 {
    let sign = select(1.0, -1.0, (bits & 0x8000u) != 0u);
    let exponent = (bits >> 10u) & 0x1fu;
    let mantissa = bits & 0x3ffu;
    if exponent == 0u {
        return sign * f32(mantissa) * 5.9604645e-8;
    }
    return bitcast<f32>(((bits & 0x8000u) << 16u) | ((exponent + 112u) << 23u) | (mantissa << 13u));
}

// packed::Block::trail_start, in the shape buffer.
fn trail_start(base: u32) -> u32 {
    return individual_at + count(base, packed::H_TRAILS);
}

// packed::layout::trail_values: values per guide of `nodes` nodes.
fn trail_values(nodes: u32) -> u32 {
    return 3u * (nodes - 1u) / 2u;
}

// sim::guides::along: guide g's offset `fraction` of the way down, linear between nodes.
fn trail_along(start: u32, g: u32, fraction: f32) -> vec3<f32> {
    let along = clamp(fraction, 0.0, 1.0) * f32(trail_nodes - 1u);
    let m = min(u32(along), trail_nodes - 2u);
    let v = along - f32(m);
    return trail_node(start, g, m) + (trail_node(start, g, m + 1u) - trail_node(start, g, m)) * v;
}

fn trail_offset(base: u32, sigma: f32, fraction: f32) -> vec3<f32> {
    let guides = count(base, packed::H_GUIDES);
    if guides == 0u {
        return vec3(0.0);
    }
    let start = trail_start(base);
    let turns = sigma / packed::TAU;
    let around = (turns - floor(turns)) * f32(guides);
    let g = min(u32(around), guides - 1u);
    let w = around - f32(g);
    let next = (g + 1u) % guides;
    let a = trail_along(start, g, fraction);
    let b = trail_along(start, next, fraction);
    return a + (b - a) * w;
}

// packed::oral_trail_offset: tube t's own guide (sim::guides::Trail::along).
fn oral_trail_offset(base: u32, t: u32, fraction: f32) -> vec3<f32> {
    if count(base, packed::H_ORAL_GUIDES) == 0u {
        return vec3(0.0);
    }
    let start = trail_start(base) + count(base, packed::H_GUIDES) * trail_stride;
    return trail_along(start, t, fraction);
}

// variation::tentacle_reach.
fn tentacle_reach(base: u32, t: u32) -> f32 {
    let seed = bitcast<u32>(individual(packed::H_SEED));
    let u = f32(pcg(seed ^ pcg(t)) >> 8u) / 16777216.0;
    return clamp(1.0 - frame_value(base + packed::H_TENTACLE_SPREAD) * u, 0.0, 1.0);
}

// tentacles::across and tentacles::perpendicular.
fn across(outward: vec3<f32>, tangent: vec3<f32>) -> vec3<f32> {
    let n = outward - dot(outward, tangent) * tangent;
    if dot(n, n) > 1e-12 {
        return normalize(n);
    }
    var other = vec3(0.0, 1.0, 0.0);
    if abs(tangent.x) < 0.9 {
        other = vec3(1.0, 0.0, 0.0);
    }
    return normalize(cross(tangent, other));
}

// shape::packed::TubeIndex: where a vertex of a run of tubes lies. `cap` is -1 for the
// cap before ring 0, 1 for the cap after the last ring, 0 for column `side` of `ring`.
struct TubeIndex {
    tube: u32,
    ring: u32,
    side: u32,
    cap: i32,
};

// shape::packed::tube_len: vertices per tube (a cap, `points` rings of `sides + 1`, a cap).
fn tube_len(sides: u32, points: u32) -> u32 {
    return 2u + points * (sides + 1u);
}

// shape::packed::tube_index: vertex `index` of a run of tubes in
// tentacles::write_topology's layout (which the oral tubes share).
fn tube_index(index: u32, sides: u32, points: u32) -> TubeIndex {
    let per = tube_len(sides, points);
    let tube = index / per;
    let r = index % per;
    if r == 0u {
        return TubeIndex(tube, 0u, 0u, -1);
    }
    if r == per - 1u {
        return TubeIndex(tube, points - 1u, 0u, 1);
    }
    return TubeIndex(tube, (r - 1u) / (sides + 1u), (r - 1u) % (sides + 1u), 0);
}

// ---- shape::oral (the manubrium and the oral arms, after the tentacles) ----

fn has_manubrium(base: u32) -> bool {
    return frame_value(base + packed::H_MANUBRIUM) > 0.5;
}

fn is_manubrium(base: u32, t: u32) -> bool {
    return has_manubrium(base) && t == 0u;
}

// OralStyle::arm_angle: (arm index, σ).
fn arm_angle(base: u32, t: u32) -> vec2<f32> {
    var first = 0u;
    if has_manubrium(base) {
        first = 1u;
    }
    let a = t - first;
    let arms = max(count(base, packed::H_ORAL) - first, 1u);
    return vec2(f32(a), packed::TAU * f32(a) / f32(arms));
}

// OralStyle::thickness.
fn oral_thickness(base: u32, manubrium: bool, f: f32) -> f32 {
    var reference = 0.15 * frame_value(base + packed::H_ARM_WIDTH);
    if manubrium {
        reference = frame_value(base + packed::H_MANUBRIUM_RADIUS);
    }
    return relative_thickness(oral_section(base, manubrium, f).y, reference);
}

// OralStyle::section: (half-width, half-thickness).
fn oral_section(base: u32, manubrium: bool, f: f32) -> vec2<f32> {
    if manubrium {
        let r = frame_value(base + packed::H_MANUBRIUM_RADIUS) * (1.0 + 0.5 * f * f);
        return vec2(r, r);
    }
    let x = clamp(f / 0.25, 0.0, 1.0);
    let grow = x * x * (3.0 - 2.0 * x);
    let half = 0.5 * frame_value(base + packed::H_ARM_WIDTH) * (0.4 + 0.6 * grow) * (1.0 - 0.6 * f * f);
    return vec2(half, 0.3 * half);
}

// oral::disc_count.
fn oral_disc_count(points: u32) -> u32 {
    return max((points - 1u) / 2u + 1u, 2u);
}

// oral::centre, between the two discs around ring m.
fn oral_centre(base: u32, t: u32, m: u32) -> vec3<f32> {
    let points = count(base, packed::H_ORAL_POINTS);
    let discs = ring_at(base, count(base, packed::H_RINGS) + 1u)
        + count(base, packed::H_POINTS) * packed::DISC;
    let n = oral_disc_count(points);
    let x = f32(m) / f32(points - 1u) * f32(n - 1u);
    let i = min(u32(x), n - 2u);
    let w = x - f32(i);
    let trail = oral_trail_offset(base, t, f32(m) / f32(points - 1u));
    if is_manubrium(base, t) {
        let a = read_disc(discs + i * packed::DISC).centre;
        let b = read_disc(discs + (i + 1u) * packed::DISC).centre;
        return a + (b - a) * w + trail;
    }
    let sigma = arm_angle(base, t).y;
    let cs = vec2(cos(sigma), sin(sigma));
    let a = disc_point(read_disc(discs + (n + i) * packed::DISC), cs);
    let b = disc_point(read_disc(discs + (n + i + 1u) * packed::DISC), cs);
    return a + (b - a) * w + trail;
}

fn oral_vertex(base: u32, index: u32) -> Surface {
    let points = count(base, packed::H_ORAL_POINTS);
    let at = tube_index(index, packed::ORAL_SIDES, points);
    let t = at.tube;
    let m = at.ring;
    let last = points - 1u;
    let c = oral_centre(base, t, m);
    let tangent = normalize_or(
        oral_centre(base, t, min(m + 1u, last)) - oral_centre(base, t, max(m, 1u) - 1u),
        vec3(0.0, -1.0, 0.0),
    );
    let manubrium = is_manubrium(base, t);
    let f = f32(m) / f32(last);
    let tissue = vec2(oral_thickness(base, manubrium, f), 0.0);
    if at.cap < 0 {
        return Surface(c - oral_section(base, manubrium, 0.0).y * tangent, -tangent, tissue);
    }
    if at.cap > 0 {
        return Surface(c + oral_section(base, manubrium, 1.0).y * tangent, tangent, tissue);
    }
    var arm = vec2(0.0, 0.0);
    if !manubrium {
        arm = arm_angle(base, t);
    }
    let aperture = read_disc(base + packed::H_APERTURE);
    let outward = disc_direction(aperture, vec2(cos(arm.y), sin(arm.y)));
    let n = across(outward, tangent);
    let b = cross(tangent, n);
    let phi = packed::TAU * f32(at.side % packed::ORAL_SIDES) / f32(packed::ORAL_SIDES);
    let e = cos(phi);
    let o = sin(phi);
    let section = oral_section(base, manubrium, f);
    var ruffle = 0.0;
    if !manubrium {
        let waves = 2.0 * sin(packed::TAU * frame_value(base + packed::H_ARM_WAVES) * f + 1.7 * arm.x);
        ruffle = frame_value(base + packed::H_ARM_FRILL) * section.x * e * e
            * (packed::ARM_CURL + waves);
    }
    let position = c + section.x * e * n + (section.y * o + ruffle) * b;
    let normal = normalize_or(section.y * e * n + section.x * o * b, n);
    return Surface(position, normal, tissue);
}

// The tentacles, then the oral tubes.
fn tentacle_vertex(base: u32, index: u32) -> Surface {
    let count_t = count(base, packed::H_TENTACLES);
    let sides = count(base, packed::H_SIDES);
    let points = count(base, packed::H_POINTS);
    let tentacles = count_t * tube_len(sides, points);
    if index >= tentacles {
        return oral_vertex(base, index - tentacles);
    }
    let at = tube_index(index, sides, points);
    let t = at.tube;
    let m = at.ring;
    let last = points - 1u;
    let centre = tentacle_centre(base, t, m);
    let tangent = normalize_or(
        tentacle_centre(base, t, min(m + 1u, last)) - tentacle_centre(base, t, max(m, 1u) - 1u),
        vec3(0.0, -1.0, 0.0),
    );
    let thin = taper(f32(m) / f32(last));
    let radius = frame_value(base + packed::H_TENTACLE_RADIUS) * thin;
    let tissue = vec2(thin, 0.0);
    if at.cap < 0 {
        return Surface(centre - radius * tangent, -tangent, tissue);
    }
    if at.cap > 0 {
        return Surface(centre + radius * tangent, tangent, tissue);
    }
    let sigma = packed::TAU * f32(t) / f32(count_t);
    let aperture = read_disc(base + packed::H_APERTURE);
    let outward = disc_direction(aperture, vec2(cos(sigma), sin(sigma)));
    let n = across(outward, tangent);
    let phi = packed::TAU * f32(at.side % sides) / f32(sides);
    let out = cos(phi) * n + sin(phi) * cross(tangent, n);
    return Surface(centre + radius * out, out, tissue);
}

@vertex
fn vertex(vertex: Vertex) -> VertexOutput {
    let tag = mesh_functions::get_tag(vertex.instance_index);
    var surface: Surface;
    if tag == packed::CPU_MESH_TAG {
        surface = cpu_vertex(vertex);
    } else {
        individual_at = offsets[tag >> 1u];
        let frame = bitcast<u32>(shapes[individual_at + packed::H_FRAME]);
        frame_is_recorded = (frame & packed::RECORDED_FRAME) != 0u;
        let base = frame & ~packed::RECORDED_FRAME;
        trail_nodes = count(base, packed::H_TRAIL_NODES);
        trail_stride = trail_values(trail_nodes);
        let local = vertex.index - mesh[vertex.instance_index].first_vertex_index;
        if (tag & 1u) == 0u {
            surface = umbrella_vertex(base, local);
        } else {
            surface = tentacle_vertex(base, local);
        }
    }

    var out: VertexOutput;
    let world_from_local = mesh_functions::get_world_from_local(vertex.instance_index);
    out.world_position = mesh_functions::mesh_position_local_to_world(
        world_from_local,
        vec4(surface.position, 1.0),
    );
    out.position = position_world_to_clip(out.world_position.xyz);

#ifdef PREPASS_PIPELINE
#ifdef UNCLIPPED_DEPTH_ORTHO_EMULATION
    out.unclipped_depth = out.position.z;
    out.position.z = min(out.position.z, 1.0);
#endif
#ifdef NORMAL_PREPASS_OR_DEFERRED_PREPASS
    out.world_normal = mesh_functions::mesh_normal_local_to_world(
        surface.normal,
        vertex.instance_index,
    );
#endif
#ifdef MOTION_VECTOR_PREPASS
    // The previous transform with this frame's shape: motion vectors see the swimming,
    // not the pulsing.
    out.previous_world_position = mesh_functions::mesh_position_local_to_world(
        mesh_functions::get_previous_world_from_local(vertex.instance_index),
        vec4(surface.position, 1.0),
    );
#endif
#else
    out.world_normal = mesh_functions::mesh_normal_local_to_world(
        surface.normal,
        vertex.instance_index,
    );
#endif

#ifdef VERTEX_UVS_A
    out.uv = vertex.uv;
#endif
#ifdef VERTEX_UVS_B
    out.uv_b = surface.tissue;
#endif
#ifdef VERTEX_OUTPUT_INSTANCE_INDEX
    out.instance_index = vertex.instance_index;
#endif
#ifdef VISIBILITY_RANGE_DITHER
    out.visibility_range_dither = mesh_functions::get_visibility_range_dither_level(
        vertex.instance_index,
        world_from_local[3],
    );
#endif
    return out;
}
