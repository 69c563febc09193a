//! Every species parameter as a row of the editor: its field, a label and the unit it is
//! shown in. Each slider spans its field's limit (`species::limits`), shown beside it,
//! and cannot leave it; limits that join fields (proportions, budgets) are validation's,
//! shown as an error above the sliders.

use crate::species::{
    Advection, BellCoupling, Bending, FringeDrag, GonadShape, Kernel, MuscleLaw, MuscleTiming,
    SliceGeometry, Species, limits,
};
use bevy_egui::egui;
use std::ops::RangeInclusive;

/// A numeric field of [`Species`], borrowed for editing.
pub enum Value<'a> {
    /// A real-valued field.
    Real(&'a mut f32),
    /// A count.
    Count(&'a mut u32),
}

/// One slider.
pub struct Param {
    /// The [`Species`] field, as named in RON files and validation errors.
    pub field: &'static str,
    /// What the slider is called in the panel.
    pub label: &'static str,
    /// The unit shown beside the value.
    pub unit: &'static str,
    /// Shown value = stored value × `scale` (lengths in millimetres).
    pub scale: f64,
    /// Whether the slider moves in ratios rather than steps (for values spanning decades).
    pub logarithmic: bool,
    /// Reaches the field in a species.
    pub value: for<'a> fn(&'a mut Species) -> Value<'a>,
}

/// A collapsible group of sliders.
pub struct Section {
    /// The section heading.
    pub title: &'static str,
    /// Its sliders, in order.
    pub params: &'static [Param],
}

macro_rules! param {
    ($field:ident, $label:literal, $unit:literal, $scale:expr, $log:expr, $kind:ident) => {
        Param {
            field: stringify!($field),
            label: $label,
            unit: $unit,
            scale: $scale,
            logarithmic: $log,
            value: |s| Value::$kind(&mut s.$field),
        }
    };
}

impl Param {
    /// The field's limit ([`limits::LIMITS`]), in the slider's units: the slider cannot
    /// leave it.
    pub fn range(&self) -> RangeInclusive<f64> {
        let limit = limits::of(self.field).expect("every slider's field has a limit");
        limit.min * self.scale..=limit.max * self.scale
    }

    /// The limit as the panel shows it beside the slider, in the slider's units.
    pub fn range_text(&self) -> String {
        let range = self.range();
        let number = |v: f64| {
            if v != 0.0 && (v.abs() < 1e-2 || v.abs() >= 1e5) {
                format!("{v:.0e}")
            } else {
                format!("{}", (v * 1e4).round() / 1e4)
            }
        };
        format!(
            "{}–{}{}",
            number(*range.start()),
            number(*range.end()),
            self.unit
        )
    }
}

const MM: f64 = 1e3;

/// The sliders, in the order the panel shows them.
#[rustfmt::skip]
pub const SECTIONS: &[Section] = &[
    Section {
        title: "Muscles",
        params: &[
            param!(contraction_frequency, "contraction frequency", " Hz", 1.0, false, Real),
            param!(natural_frequency, "natural pulse rate", " Hz", 1.0, false, Real),
            param!(natural_diameter, "at diameter", " mm", MM, true, Real),
            param!(contraction_ratio, "contracted length", "", 1.0, false, Real),
            param!(contraction_duty, "contraction duty", "", 1.0, false, Real),
            param!(relaxation_span, "relaxation span", "", 1.0, false, Real),
            param!(expansion_stagger, "expansion stagger", "", 1.0, false, Real),
            param!(muscle_extent, "muscle extent", "", 1.0, false, Real),
            param!(muscle_modulus, "muscle modulus", " Pa", 1.0, true, Real),
            param!(muscle_cross_section, "muscle cross-section", "", 1.0, true, Real),
        ],
    },
    Section {
        title: "Bell",
        params: &[
            param!(diameter, "diameter", " mm", MM, true, Real),
            param!(height, "height", " mm", MM, true, Real),
            param!(thickness, "mesoglea thickness", " mm", MM, true, Real),
            param!(margin_thickness_ratio, "margin thickness", "", 1.0, false, Real),
            param!(elastic_modulus, "mesoglea stiffness", " Pa", 1.0, true, Real),
            param!(angular_stiffness, "bending stiffness", " N·m/rad", 1.0, true, Real),
            param!(hoop_cross_section, "hoop cross-section", "", 1.0, true, Real),
            param!(mesoglea_resilience, "mesoglea resilience", "", 1.0, false, Real),
        ],
    },
    Section {
        title: "Tentacles",
        params: &[
            param!(tentacle_count, "tentacles", "", 1.0, false, Count),
            param!(tentacle_length, "length", " mm", MM, false, Real),
            param!(tentacle_radius, "radius", " mm", MM, true, Real),
            param!(tentacle_length_spread, "length spread", "", 1.0, false, Real),
            param!(tentacle_guides, "guide chains", "", 1.0, false, Count),
            param!(tentacle_cross_section, "spring cross-section", "", 1.0, true, Real),
        ],
    },
    Section {
        title: "Anatomy",
        params: &[
            param!(manubrium_length, "manubrium length", " mm", MM, false, Real),
            param!(manubrium_radius, "manubrium radius", " mm", MM, true, Real),
            param!(oral_arm_count, "oral arms", "", 1.0, false, Count),
            param!(oral_arm_length, "arm length", " mm", MM, false, Real),
            param!(oral_arm_width, "arm width", " mm", MM, true, Real),
            param!(oral_arm_frill, "arm frill", "", 1.0, false, Real),
            param!(gonad_count, "gonads", "", 1.0, false, Count),
            param!(gonad_size, "gonad size", "", 1.0, false, Real),
            param!(radial_canal_count, "radial canals", "", 1.0, false, Count),
            param!(canal_width, "canal width", "", 1.0, false, Real),
        ],
    },
    Section {
        title: "Surface variation",
        params: &[
            param!(structural_scale, "structural scale", "", 1.0, false, Real),
            param!(structural_frequency, "structural lobes", "", 1.0, false, Real),
            param!(compression_scale, "compression scale", "", 1.0, false, Real),
            param!(compression_frequency, "compression ripples", "", 1.0, false, Real),
            param!(unstructured_scale, "noise scale", "", 1.0, false, Real),
            param!(noise_frequency_lat, "noise frequency, latitude", "", 1.0, false, Real),
            param!(noise_frequency_lon, "noise frequency, longitude", "", 1.0, false, Real),
            param!(noise_frequency_time, "noise frequency, time", " /s", 1.0, false, Real),
        ],
    },
    Section {
        title: "Water",
        params: &[
            param!(grid_resolution, "grid cells per side", "", 1.0, false, Count),
            param!(domain_diameters, "domain", " diameters", 1.0, false, Real),
            param!(boundary_width, "boundary width", " diameters", 1.0, false, Real),
            param!(viscosity, "viscosity", " Pa·s", 1.0, true, Real),
            param!(density, "density", " kg/m³", 1.0, false, Real),
        ],
    },
    Section {
        title: "Mesh",
        params: &[
            param!(mesh_rings, "rings", "", 1.0, false, Count),
            param!(mesh_segments, "segments", "", 1.0, false, Count),
            param!(tentacle_sides, "tentacle sides", "", 1.0, false, Count),
        ],
    },
    Section {
        title: "Looks",
        params: &[
            param!(glow, "glow", "", 1.0, false, Real),
            param!(glow_band, "glow band", "", 1.0, false, Real),
        ],
    },
    Section {
        title: "Touch",
        params: &[
            param!(flash, "flash", "", 1.0, false, Real),
            param!(flash_decay, "flash decay", " s", 1.0, false, Real),
            param!(flash_refractory, "refractory", " s", 1.0, false, Real),
            param!(touch_reach, "touch reach", " diameters", 1.0, false, Real),
            param!(echo_reach, "echo reach", " diameters", 1.0, false, Real),
            param!(echo_delay, "echo delay", " s", 1.0, false, Real),
            param!(escape_depth, "escape depth", "", 1.0, false, Real),
            param!(escape_rhythm, "escape rhythm", "×", 1.0, false, Real),
            param!(escape_strokes, "escape strokes", "", 1.0, false, Count),
        ],
    },
];

/// Fields edited by a widget other than a slider (see [`species_controls`]).
pub const OTHER_FIELDS: &[&str] = &[
    "name",
    "slice_geometry",
    "bending",
    "fringe_drag",
    "muscle_law",
    "muscle_timing",
    "advection",
    "kernel",
    "bell_coupling",
    "structural_abs",
    "gonad_shape",
    "gonad_color",
    "bell_color",
    "glow_color",
];

/// Draws one slider; true if the user changed the value.
fn slider(ui: &mut egui::Ui, param: &Param, species: &mut Species) -> bool {
    let mut shown = match (param.value)(species) {
        Value::Real(v) => *v as f64 * param.scale,
        Value::Count(v) => *v as f64,
    };
    ui.label(param.label).on_hover_text(param.field);
    let mut widget = egui::Slider::new(&mut shown, param.range())
        .logarithmic(param.logarithmic)
        .clamping(egui::SliderClamping::Always)
        .suffix(param.unit);
    if matches!((param.value)(species), Value::Count(_)) {
        widget = widget.integer();
    }
    let limit = limits::of(param.field).map_or("", |l| l.why);
    // The springs' constant is not read while the mesoglea bends the bell.
    let read = param.field != "angular_stiffness" || species.bending == Bending::Springs;
    let changed = ui
        .add_enabled(read, widget)
        .on_disabled_hover_text("read only with bending: Springs")
        .changed();
    ui.label(egui::RichText::new(param.range_text()).weak().small())
        .on_hover_text(limit);
    ui.end_row();
    if changed {
        match (param.value)(species) {
            Value::Real(v) => *v = (shown / param.scale) as f32,
            Value::Count(v) => *v = shown.round().clamp(0.0, u32::MAX as f64) as u32,
        }
    }
    changed
}

/// Every parameter of `species` as a widget, grouped in sections; true if any changed.
pub fn species_controls(ui: &mut egui::Ui, species: &mut Species) -> bool {
    let mut changed = false;
    for section in SECTIONS {
        egui::CollapsingHeader::new(section.title)
            .default_open(section.title == "Muscles")
            .show(ui, |ui| {
                egui::Grid::new(section.title)
                    .num_columns(3)
                    .striped(true)
                    .show(ui, |ui| {
                        for param in section.params {
                            changed |= slider(ui, param, species);
                        }
                        match section.title {
                            "Surface variation" => {
                                ui.label("lobes as |sin|").on_hover_text("structural_abs");
                                changed |= ui.checkbox(&mut species.structural_abs, "").changed();
                                ui.end_row();
                            }
                            "Muscles" => {
                                changed |= muscle_law(ui, &mut species.muscle_law);
                                changed |= muscle_timing(ui, &mut species.muscle_timing);
                            }
                            "Bell" => changed |= bending(ui, &mut species.bending),
                            "Tentacles" => changed |= fringe_drag(ui, &mut species.fringe_drag),
                            "Anatomy" => {
                                changed |= gonad_shape(ui, &mut species.gonad_shape);
                                ui.label("gonad colour").on_hover_text("gonad_color");
                                changed |= ui
                                    .color_edit_button_rgba_unmultiplied(&mut species.gonad_color)
                                    .changed();
                                ui.end_row();
                            }
                            "Water" => {
                                changed |= slice_geometry(ui, &mut species.slice_geometry);
                                changed |= advection(ui, &mut species.advection);
                                changed |= kernel(ui, &mut species.kernel);
                                changed |= bell_coupling(ui, &mut species.bell_coupling);
                            }
                            "Looks" => {
                                ui.label("bell colour").on_hover_text("bell_color");
                                changed |= ui
                                    .color_edit_button_rgba_unmultiplied(&mut species.bell_color)
                                    .changed();
                                ui.end_row();
                                ui.label("glow colour").on_hover_text("glow_color");
                                changed |=
                                    ui.color_edit_button_rgb(&mut species.glow_color).changed();
                                ui.end_row();
                            }
                            _ => {}
                        }
                    });
            });
    }
    changed
}

/// A row with a drop-down of every value of the enumerated field `field`, labelled
/// `label`, with `why` on hover; true if the user picked another.
fn picker<T: Copy + PartialEq + std::fmt::Debug>(
    ui: &mut egui::Ui,
    field: &str,
    label: &str,
    why: &str,
    value: &mut T,
    all: &[T],
) -> bool {
    ui.label(label).on_hover_text(format!("{field}: {why}"));
    let before = *value;
    egui::ComboBox::from_id_salt(field)
        .selected_text(format!("{value:?}"))
        .show_ui(ui, |ui| {
            for &v in all {
                ui.selectable_value(value, v, format!("{v:?}"));
            }
        });
    ui.end_row();
    *value != before
}

fn slice_geometry(ui: &mut egui::Ui, geometry: &mut SliceGeometry) -> bool {
    let why = "Planar is the paper's slice (a vortex-pair wake); Axisymmetric is a body of \
               revolution (every point a ring, a vortex-ring wake); changing it rebuilds \
               the slice at rest";
    let all = &SliceGeometry::ALL;
    picker(ui, "slice_geometry", "slice geometry", why, geometry, all)
}

fn bending(ui: &mut egui::Ui, bending: &mut Bending) -> bool {
    let why = "Mesoglea bends the wall as a plate of its own modulus and thickness, E·ϑ³/12, \
               so resized or stiffened the bell keeps a rigidity that fits it; Springs \
               takes the paper's angular springs, the bending stiffness above";
    picker(ui, "bending", "bending", why, bending, &Bending::ALL)
}

fn muscle_law(ui: &mut egui::Ui, law: &mut MuscleLaw) -> bool {
    let why = "in the axisymmetric slice, Force makes the muscle a force generator (the \
               stroke, the refill and the best pulse rate are the bell's); Length commands \
               its rest length, the paper's planar spring carried into r–z (the plane \
               always takes the paper's)";
    let all = &MuscleLaw::ALL;
    picker(ui, "muscle_law", "muscle law", why, law, all)
}

fn muscle_timing(ui: &mut egui::Ui, timing: &mut MuscleTiming) -> bool {
    let why = "Twitch keeps the muscle's contraction and release as long as at the natural \
               pulse rate for the bell's size, so beaten much faster the muscle never lets go \
               (the animals); Cycle makes them fractions of any cycle (the paper's)";
    let all = &MuscleTiming::ALL;
    picker(ui, "muscle_timing", "muscle timing", why, timing, all)
}

fn fringe_drag(ui: &mut egui::Ui, law: &mut FringeDrag) -> bool {
    let why = "Filaments drags each tentacle as a slender cylinder, by skin friction along \
               it (the animals); Curtain lets a dense fringe carry its water and drag as \
               much along as across (the paper's immersed tentacles)";
    let all = &FringeDrag::ALL;
    picker(ui, "fringe_drag", "fringe drag", why, law, all)
}

fn advection(ui: &mut egui::Ui, advection: &mut Advection) -> bool {
    let why = "semi-Lagrangian is the steadiest; MacCormack and Cubic have less numerical \
               viscosity";
    let all = &Advection::ALL;
    picker(ui, "advection", "advection", why, advection, all)
}

fn gonad_shape(ui: &mut egui::Ui, shape: &mut GonadShape) -> bool {
    let why = "how the gonads are drawn through the bell";
    let all = &GonadShape::ALL;
    picker(ui, "gonad_shape", "gonad shape", why, shape, all)
}

fn bell_coupling(ui: &mut egui::Ui, coupling: &mut BellCoupling) -> bool {
    let why = "what the bell's solve expects of the water: AddedMass is what the shipped \
               species are calibrated with, WaterResponse keeps the wall from giving";
    let all = &BellCoupling::ALL;
    picker(ui, "bell_coupling", "bell coupling", why, coupling, all)
}

fn kernel(ui: &mut egui::Ui, kernel: &mut Kernel) -> bool {
    let why = "how the bell meets the water; Roma3 does not see the grid, Bilinear is the \
               paper's";
    picker(ui, "kernel", "kernel", why, kernel, &Kernel::ALL)
}
