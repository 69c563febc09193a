//! The shipped species (as in `assets/species/`) and the paper's own variations and
//! numerics, one call away.

use super::{
    Advection, BellCoupling, Bending, FringeDrag, GonadShape, Kernel, MuscleLaw, MuscleTiming,
    SliceGeometry, Species,
};

impl Species {
    /// The moon jelly, *Aurelia aurita*, a young medusa of 40 mm shaped and timed from
    /// records of the animal (`assets/species/aurelia.species.ron`, `docs/physics.md`
    /// section 5): a saucer a quarter as deep as it is wide that contracts quickly to a
    /// half-dome and refills slowly, in the axisymmetric slice whose ring wake it rows with.
    pub fn aurelia() -> Self {
        // Apex mesoglea of 3 mm (below), plate bending E·ϑ³/12 per 2 mm hinge as `paper`.
        let thickness = 0.003;
        Self {
            name: "Aurelia".into(),
            // A body of revolution rows with vortex rings; the planar slice's vortex pairs
            // carry a flat bell's stroke a third less far (`docs/numerics.md`).
            slice_geometry: SliceGeometry::Axisymmetric,
            // Three and a half diameters keep the bell at seventeen cells per diameter on
            // the paper's grid of 60, and the band where it meets the water at 0.25 D (four
            // and a half cells; the real mesoglea is 0.125 D). With the force-generating
            // muscle the stroke needs them: at fifteen cells and 0.2 D it grew 18% from
            // grid 60 to 90, here 15%, still growing towards about 0.55 D at grid 135; a
            // 0.3 D band held 13% but pumped the bell backwards on finer grids
            // (`docs/numerics.md`).
            domain_diameters: 3.5,
            boundary_width: 0.25,
            // A saucer: its subumbrella 0.26 D deep, as the 15.5 cm animal Dabiri recorded
            // (2011; 40.5 mm from apex to margin on 156.5 mm, as the SimpleAurelia model
            // prescribes it) and the 0.25–0.3 of *Aurelia*'s bells generally, under an apex
            // of mesoglea 0.075 D thick (the record's 0.125 D lens, thinned where the slice
            // would otherwise be a third deeper than the animal seen from outside: the
            // whole bell 0.34 D tall; `docs/physics.md` section 5).
            height: 0.0104,
            thickness,
            // The bell bends as a plate of its mesoglea, E·ϑ³/12, so resized or stiffened it
            // keeps a rigidity that fits it; the springs' constant below is the same number
            // at this size, for `Bending::Springs`.
            bending: Bending::Mesoglea,
            angular_stiffness: 1186.0 * thickness * thickness * thickness / 12.0 / 0.002,
            // The mesoglea gives back 58% of its strain energy over a stroke (DeMont &
            // Gosline 1988, *Polyorchis*; no figure for *Aurelia*), not the paper's all of
            // it: an undamped bell rang after its muscle let go, and the 155 mm animal's
            // apex snapped through under its stroke.
            mesoglea_resilience: 0.58,
            // The same animal contracts in 0.80 s of its 2.87 s cycle. Its muscle lets go
            // well before the bell has refilled (over half the time to the next stroke, as
            // the paper's): the slow reopening of the margin is the mesoglea's recoil, an
            // outcome (`examples/kinematics.rs`). At 40 mm it pulses about twice as often
            // as at 15.5 cm (0.35 Hz): frequency falling with size as McHenry & Jed (2003)
            // report, taken here as D^(-1/2).
            contraction_frequency: 0.7,
            contraction_duty: 0.28,
            relaxation_span: 0.5,
            // The band nearest the margin lets go later and more slowly than the rest, 0.7
            // as much later as the paper's stagger: the least change from it that has the
            // margin back to its width when the next stroke begins, as the record's is
            // (0.99 at phase 0.97; the paper's stagger held it at 0.89). Through the whole
            // stroke it fits the record's margin and outline better too (rms 0.079 and
            // 0.059 of the diameter against 0.100 and 0.074; at 15.5 cm 0.099 and 0.074
            // against 0.118 and 0.084; `docs/physics.md` section 5).
            expansion_stagger: 0.7,
            // Those are the muscle's twitch: 0.40 s to contract and 0.51 s to let go at
            // 40 mm, whatever the rate it is made to beat at. Beaten faster than they fit,
            // the muscle fires again before it has let go.
            muscle_timing: MuscleTiming::Twitch,
            natural_frequency: 0.7,
            natural_diameter: 0.04,
            // A force generator: the bell's stroke, its refill and its best pulse rate are
            // outcomes of the muscle's pull against the bell and its water.
            muscle_law: MuscleLaw::Force,
            // Its swimming (coronal) muscle is a band on the margin's quarter of the
            // subumbrella's arc, outside the ring of gonads and gastric pouches: held open by
            // its own hoops the upper bell bulges over a margin the band pulls in, and the
            // cavity contracts to about a half-dome (0.6 of its width deep) where a muscle
            // over the outer half draws it 0.77 deep (`docs/physics.md` section 5).
            muscle_extent: 0.25,
            // The band pulls to 0.62 of its length, so the margin closes to 0.62 of its
            // rest width, near the animal's 0.64 (Bajcar et al. 2009: the radius varies by
            // about 36%); the paper's 0.56 closes this saucer's margin to 0.56.
            contraction_ratio: 0.62,
            // Hundreds of fine marginal tentacles, each a slender cylinder in the water,
            // 12.5 mm long (0.31 D). The records span a short fringe to one "about as long
            // as disc diameter" (the Marine Species Identification Portal's A. aurita);
            // one as long as the disc takes a third of the stroke and draws the
            // bell back while it refills, where the animal glides (Gemmell et al. 2013).
            // At 12.5 mm it slows the bell 8% (11% at 20 mm, 4% at 80 mm), in the 5–30%
            // that tentacles cost a bell (Miles & Battista 2019); at 5 mm (until
            // 2026-12-06) it cost 1%, rowing as a skirt as much as it dragged.
            tentacle_count: 200,
            tentacle_length: 0.0125,
            fringe_drag: FringeDrag::Filaments,
            ..Self::paper()
        }
    }

    /// The moon jelly of the paper's Fig. 12 (Rudolf & Mould 2009), in SI units, simulated
    /// in a compact box that follows the bell (see [`Species::with_paper_numerics`] for the
    /// paper's own box): a tall dome with a slow, deep stroke. Kept to reproduce the
    /// paper's findings (staggered re-expansion beats unison, an interior frequency peak
    /// that moves with stiffness); [`Species::aurelia`] is the animal.
    pub fn paper() -> Self {
        Self {
            name: "Paper".into(),
            grid_resolution: 60,
            viscosity: 1.304e-3,
            density: 1025.0,
            domain_diameters: 6.0,
            slice_geometry: SliceGeometry::Planar,
            advection: Advection::SemiLagrangian,
            kernel: Kernel::Roma3,
            bell_coupling: BellCoupling::AddedMass,
            boundary_width: 0.3,
            diameter: 0.040,
            height: 0.028,
            thickness: 0.004,
            margin_thickness_ratio: 0.3,
            elastic_modulus: 1186.0,
            // Plate bending of the apex wall, E·ϑ³/12 per 2 mm hinge (`docs/physics.md` §2).
            bending: Bending::Springs,
            angular_stiffness: 1186.0 * 0.004 * 0.004 * 0.004 / 12.0 / 0.002,
            mesoglea_resilience: 1.0,
            muscle_modulus: 400.0e3,
            muscle_cross_section: 0.01,
            // Calibrated: puts the bell's resonance with its water near the paper's 0.7 Hz
            // (the distance swum in 20 s peaks between 0.7 and 1 Hz).
            hoop_cross_section: 0.0101,
            contraction_frequency: 0.7,
            // Its stroke is a fraction of whatever cycle it beats: the paper's sweep.
            muscle_timing: MuscleTiming::Cycle,
            natural_frequency: 0.7,
            natural_diameter: 0.040,
            contraction_ratio: 0.56,
            contraction_duty: 0.35,
            relaxation_span: 0.5,
            expansion_stagger: 1.0,
            // The paper's muscle springs, from the margin three quarters of the way up to
            // the apex (its Fig. 4).
            muscle_extent: 0.75,
            // In the plane its springs' rest lengths follow the contraction, as the paper's;
            // in r–z, where every ring has its hoop, a force generator, as the animals'
            // (its sweep then peaks at 1 Hz, and at 1.4 Hz with a bell twice as stiff).
            muscle_law: MuscleLaw::Force,
            // A moon jelly's fringe: hundreds of short, fine marginal tentacles. Their drag
            // slows the bell by about a tenth (Miles & Battista 2019: tentacles reduce
            // forward speed; measured here 9%, `tests/slice.rs`). The paper's tentacles
            // are immersed chains that move with their water, as a dense fringe does in
            // the curtain law.
            tentacle_count: 200,
            tentacle_length: 0.015,
            tentacle_cross_section: 0.01,
            tentacle_radius: 0.00015,
            fringe_drag: FringeDrag::Curtain,
            tentacle_length_spread: 0.35,
            // A current past the bell is a first harmonic around the margin and a turn a
            // second; eight guides draw both and their lag across a fringe of 200.
            tentacle_guides: 8,
            // Four frilly oral arms from a short manubrium, four horseshoe gonads between
            // them and sixteen radial canals: how a moon jelly is recognised.
            manubrium_length: 0.003,
            manubrium_radius: 0.0015,
            oral_arm_count: 4,
            oral_arm_length: 0.03,
            oral_arm_width: 0.003,
            oral_arm_frill: 0.5,
            gonad_count: 4,
            gonad_shape: GonadShape::Horseshoe,
            gonad_size: 0.3,
            gonad_color: [0.85, 0.45, 0.95, 0.9],
            radial_canal_count: 16,
            canal_width: 0.008,
            // A smooth, taut bell, as in photographs of living medusae: gentle lobes, faint
            // ripples as it contracts, a hint of irregularity. The paper's Fig. 12 values,
            // several times larger, crumple the dome: `with_paper_variations`.
            structural_scale: 0.06,
            structural_frequency: 8.0,
            structural_abs: false,
            compression_scale: 0.08,
            compression_frequency: 8.0,
            unstructured_scale: 0.3,
            noise_frequency_lat: 2.0,
            noise_frequency_lon: 8.0,
            noise_frequency_time: 0.01,
            mesh_rings: 24,
            mesh_segments: 48,
            // Hair-thin tubes: three sides read as round at any size they are seen at,
            // and keep two hundred of them under 11,000 vertices.
            tentacle_sides: 3,
            bell_color: [0.75, 0.85, 1.0, 0.35],
            glow_color: [0.35, 0.55, 1.0],
            glow: 0.6,
            // The band is a look, not biology: no medusa is known to glow with its stroke.
            glow_band: 0.8,
            // Scyphozoans like the moon jelly do not luminesce (Haddock, Moline & Case
            // 2010); touched, it only quickens its strokes for a couple of cycles.
            flash: 0.0,
            flash_decay: 0.8,
            flash_refractory: 2.0,
            touch_reach: 1.0,
            echo_reach: 0.0,
            echo_delay: 0.3,
            escape_depth: 0.2,
            escape_rhythm: 1.3,
            escape_strokes: 2,
        }
    }

    /// The crystal jelly, *Aequorea* (`assets/species/aequorea.species.ron`): a saucer thick
    /// in its centre and thinning to a flexible margin, with a hundred long fine tentacles,
    /// slow strokes and a green glow, in the axisymmetric slice whose paired vortex rings it
    /// rows with (`docs/physics.md` section 5).
    pub fn aequorea() -> Self {
        // "Thick in centre, gradually thinning towards margin": the apex's mesoglea an
        // eighth of the diameter, as the moon jelly's measured one (no figure for
        // *Aequorea*); plate bending E·ϑ³/12 per 2 mm hinge, as the other species.
        let thickness = 0.0075;
        Self {
            name: "Aequorea".into(),
            // A rower whose wake is pairs of opposite vortex rings shed close together at
            // its margin; Sahin, Mohseni & Colin (2009) simulate it in swirl-free
            // cylindrical coordinates.
            slice_geometry: SliceGeometry::Axisymmetric,
            // Twelve cells per diameter and the band at the kernel's three cells (0.25 D):
            // grids G..G+3 within 2.3%, G to 1.5·G +3.4%, with a fifth fewer steps than
            // the moon jelly's fifteen cells (`docs/numerics.md`).
            domain_diameters: 5.0,
            boundary_width: 0.25,
            // "Umbrella saucer-shaped" (the Marine Species Identification Portal's
            // *A. forskalea* and *A. vitrina*, after Kramp 1961 and Russell 1970): 60 mm
            // wide, a subumbrellar cavity 0.15 D deep under its 0.125 D apex, the whole bell
            // 0.275 D tall. The old bowl, a 20 mm cavity under a 5 mm wall (0.42 D), was
            // not from the animal.
            diameter: 0.06,
            height: 0.009,
            thickness,
            bending: Bending::Mesoglea,
            angular_stiffness: 1186.0 * thickness * thickness * thickness / 12.0 / 0.002,
            // The mesoglea's measured resilience, as the moon jelly's (DeMont & Gosline
            // 1988, measured on a hydromedusa, *Polyorchis*).
            mesoglea_resilience: 0.58,
            // The moon jelly's muscle: a force generator, lining the subumbrella outside
            // the stomach, a dish half as wide as the disc (below).
            muscle_law: MuscleLaw::Force,
            muscle_extent: 0.5,
            margin_thickness_ratio: 0.25,
            // Its pulse rate and stroke are not from a record of it (the published
            // kinematics were out of reach): the one rower we have a record of, the moon
            // jelly, lends its timing (a contraction of 0.28 of the cycle, the muscle letting
            // go over half the refill) and its muscle, at 0.6 Hz, the moon jelly's rate at
            // 60 mm within 5% (D^(-1/2) from 0.7 Hz at 40 mm).
            contraction_frequency: 0.6,
            muscle_timing: MuscleTiming::Twitch,
            natural_frequency: 0.6,
            natural_diameter: 0.06,
            contraction_duty: 0.28,
            contraction_ratio: 0.56,
            // The paper's staggered release, the moon jelly's before its refill was fitted
            // to its record: with the moon jelly's 0.7 this flat bell is drawn back while it
            // refills at 30 mm (−0.014 D/s), and no record of *Aequorea*'s refill was in
            // reach to choose between them.
            expansion_stagger: 1.0,
            // A hundred long, fine tentacles, three quarters of the bell long: chosen.
            // Slender cylinders: along its length the fringe drags by skin friction.
            tentacle_count: 100,
            tentacle_length: 0.045,
            tentacle_radius: 0.00025,
            fringe_drag: FringeDrag::Filaments,
            // Some of a crystal jelly's long tentacles hang full length, others curled up.
            tentacle_length_spread: 0.6,
            tentacle_guides: 8,
            tentacle_sides: 4,
            // A short stomach fringed with lips; gonads along its many radial canals (60–80
            // in the animal; tentacles "from half to twice as many"). The animal's stomach
            // is "half as wide as disc", a shallow dish on the subumbrella: the manubrium
            // is drawn as a hanging tube, and one that wide pokes through the contracted
            // apex, so it keeps the tube's 4 mm. Stomach and lips reach 7 mm, within the
            // 9 mm cavity: they follow the slice alone (`oral_tubes_within_cavity`).
            manubrium_length: 0.003,
            manubrium_radius: 0.004,
            oral_arm_count: 12,
            oral_arm_length: 0.004,
            oral_arm_width: 0.0015,
            oral_arm_frill: 0.8,
            gonad_count: 60,
            gonad_shape: GonadShape::Radial,
            gonad_size: 0.45,
            gonad_color: [0.85, 1.0, 0.9, 0.45],
            radial_canal_count: 60,
            canal_width: 0.006,
            structural_scale: 0.05,
            structural_frequency: 16.0,
            structural_abs: true,
            compression_frequency: 12.0,
            unstructured_scale: 0.2,
            bell_color: [0.8, 0.95, 0.9, 0.25],
            glow_color: [0.3, 1.0, 0.45],
            glow: 0.5,
            glow_band: 0.5,
            // Its photocytes ring the margin and flash green when it is touched (Davenport
            // & Nicol 1955; aequorin's blue handed to GFP, Shimomura et al. 1962); how
            // bright, how long and how often are chosen to read, not measured.
            flash: 4.0,
            flash_decay: 0.8,
            flash_refractory: 2.0,
            echo_reach: 4.0,
            escape_depth: 0.25,
            escape_rhythm: 1.3,
            escape_strokes: 3,
            ..Self::paper()
        }
    }

    /// The clapper hydromedusa, *Sarsia tubulosa* (`assets/species/sarsia.species.ron`): a
    /// bell a little taller than wide that jets with quick, deep strokes, four long
    /// tentacles and a long tubular manubrium, in the axisymmetric slice whose vortex ring
    /// it jets with (`docs/physics.md` section 5).
    pub fn sarsia() -> Self {
        // "Moderately thick jelly" (no measured figure); plate bending E·ϑ³/12 per 2 mm
        // hinge, as the other species.
        let thickness = 0.0025;
        Self {
            name: "Sarsia".into(),
            // A prolate jetter's wake is one vortex ring a stroke (Sahin, Mohseni & Colin
            // 2009, who simulate it axisymmetric; Katija et al. 2015).
            slice_geometry: SliceGeometry::Axisymmetric,
            // Ten cells per diameter, as the paper's; the band where the bell meets the
            // water 0.2 D, nearer its 0.16 D wall than the kernel's three cells reach on
            // this grid (0.3 D), so a finer grid thins the band towards the wall. A jet is
            // a thin shear layer that semi-Lagrangian advection smears (its stroke gained
            // 29% from grid 60 to 90); limited bicubic sampling keeps it within 7%, and
            // fifteen cells per diameter cost 1.7 times as much for no closer a figure
            // (`docs/numerics.md`, "Sarsia in r–z").
            domain_diameters: 6.0,
            boundary_width: 0.2,
            advection: Advection::Cubic,
            // "Umbrella up to 18 mm high, somewhat higher than wide" (the Marine Species
            // Identification Portal's *S. tubulosa*): 16 mm wide and 18 mm from apex to
            // margin, so a subumbrellar cavity of 15.5 mm under its apex.
            diameter: 0.016,
            height: 0.0155,
            thickness,
            bending: Bending::Mesoglea,
            angular_stiffness: 1186.0 * thickness * thickness * thickness / 12.0 / 0.002,
            margin_thickness_ratio: 0.4,
            // Pulse rate and the depth and timing of the stroke are not from a record (the
            // published kinematics were out of reach): a jetter's quick, deep strokes.
            // The muscle lets go over three quarters of the refill, the band nearest the
            // margin later (the paper's stagger), and the bell glides forwards while it
            // refills, as a jetter does (Colin & Costello 2002). Over the whole refill
            // (chosen until 2026-12-05) every band let go alike and the stagger did
            // nothing; over the paper's half, beaten at half its rate the bell is drawn
            // back while it rests. Chosen, not measured; outcomes in
            // `examples/kinematics.rs`.
            contraction_frequency: 1.4,
            contraction_ratio: 0.5,
            contraction_duty: 0.3,
            relaxation_span: 0.75,
            // A twitch, as the rowers' muscle (`muscle_timing` from the moon jelly): at
            // its own rate it lets go just as it fires again.
            muscle_timing: MuscleTiming::Twitch,
            natural_frequency: 1.4,
            natural_diameter: 0.016,
            // The paper's muscle, whose rest length the contraction sets. As a force
            // generator (the other species' muscle) its thin margin folded inward while
            // the bell refilled: 8 recoveries in 30 strokes with the muscle letting go over
            // half the refill, 2 at grid 78 in a box of five (`docs/physics.md`).
            muscle_law: MuscleLaw::Length,
            // Its stomach hangs at the end of the long manubrium, not on the subumbrella:
            // the paper's three quarters of the arc.
            muscle_extent: 0.75,
            // The paper's lossless mesoglea, with which that commanded stroke was chosen
            // (the other species' measured 58% goes with their force generator).
            mesoglea_resilience: 1.0,
            tentacle_count: 4,
            tentacle_length: 0.025,
            tentacle_radius: 0.0003,
            fringe_drag: FringeDrag::Filaments,
            tentacle_length_spread: 0.15,
            // One guide per tentacle: each of the four trails on its own.
            tentacle_guides: 4,
            tentacle_sides: 6,
            // The long tubular manubrium it is named for hangs out of the bell (in the
            // animal up to 2.5 times the bell's height; here 1.4, which keeps it inside the
            // slice's box of four diameters that carries it), four radial canals.
            manubrium_length: 0.025,
            manubrium_radius: 0.0008,
            oral_arm_count: 0,
            oral_arm_length: 0.0,
            gonad_count: 0,
            radial_canal_count: 4,
            canal_width: 0.025,
            structural_scale: 0.04,
            structural_frequency: 4.0,
            unstructured_scale: 0.15,
            bell_color: [0.95, 0.8, 0.85, 0.3],
            glow_color: [1.0, 0.35, 0.5],
            glow: 0.5,
            glow_band: 0.5,
            // A jetter: touched, it beats much deeper and quicker for a few strokes.
            escape_depth: 0.4,
            escape_rhythm: 1.3,
            escape_strokes: 3,
            ..Self::paper()
        }
    }

    /// Every shipped species, as in `assets/species/`.
    pub fn presets() -> [Species; 3] {
        [Self::aurelia(), Self::aequorea(), Self::sarsia()]
    }

    /// The paper's surface variation (its Fig. 9 and 12): structural lobes 0.375, compression
    /// ripples 0.15 and Perlin noise 2.25 of the thickness, eight lobes and ripples. Only the
    /// shape changes, not the slice. The shipped species are smoother.
    pub fn with_paper_variations(mut self) -> Self {
        self.structural_scale = 0.375;
        self.structural_frequency = 8.0;
        self.structural_abs = false;
        self.compression_scale = 0.15;
        self.compression_frequency = 8.0;
        self.unstructured_scale = 2.25;
        self.noise_frequency_lat = 2.0;
        self.noise_frequency_lon = 8.0;
        self.noise_frequency_time = 0.01;
        self
    }

    /// The paper's numerics (its Fig. 12 and section 3.2): grid 100 over a box ten
    /// diameters wide, bilinear spreading, semi-Lagrangian advection. The physics is the
    /// same; [`Species::paper`] keeps the resolution (ten cells per diameter) in a
    /// six-diameter box that follows the bell, with a kernel that does not see the grid.
    pub fn with_paper_numerics(mut self) -> Self {
        self.grid_resolution = 100;
        self.domain_diameters = 10.0;
        self.kernel = Kernel::Bilinear;
        self.advection = Advection::SemiLagrangian;
        self
    }
}
