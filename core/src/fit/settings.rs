//! The model's settings (method.md sections 3, 5, 11 and 12): the DMP's
//! basis and phase, S's standardisation, how the skill error follows each
//! demo's start and goal, and the orientation's options.

use serde::{Deserialize, Serialize};

use crate::fit::mapping::Scaling;

/// DMP settings (method.md section 3; the paper's values are the defaults).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DmpSettings {
    /// Number of basis functions `B`.
    pub basis_functions: usize,
    /// Decay of the canonical system, `alpha_x` (ln 100 puts x(1) at 0.01).
    pub alpha_x: f64,
    /// S's standardisation, an option beyond the method (method.md section
    /// 5): each axis's SD of a demo's target forcing term is floored at
    /// this fraction of that demo's largest axis SD, so an axis that barely
    /// moves is not blown up to unit variance. 0 (the default) is the
    /// method as written.
    #[serde(default)]
    pub axis_sd_floor: f64,
    /// How the skill error E follows each demo's start and goal (method.md
    /// section 11).
    #[serde(default)]
    pub skill_mode: SkillMode,
    /// The weight of the orientation error in J, per degree: `J = S + k
    /// sum d + k_rot sum d_rot` with `d_rot` in degrees (an option beyond
    /// the method, `--k-rot`; 0, the default, leaves J the paper's).
    #[serde(default)]
    pub k_rot: f64,
    /// Separate gains `[D/M, K/M]` for the orientation DMP (`None`, the
    /// default: the position's, one pair for the pose as method.md section
    /// 12 says); `--orientation-gains`.
    #[serde(default)]
    pub orientation_gains: Option<[f64; 2]>,
    /// Whether the landscape maps `sum d_rot` (method.md section 12):
    /// the orientation's kernel costs about twice the position's, so the
    /// app computes the map when it is shown (or `k_rot` needs it); the
    /// CLI always. Each evaluated point (Table I, the operating point) has
    /// its d_rot either way.
    /// (Settings saved before the option read as off, as the app's default.)
    #[serde(default)]
    pub orientation_map: bool,
}

impl Default for DmpSettings {
    fn default() -> Self {
        Self {
            basis_functions: 100,
            alpha_x: crate::portable::ln(100.0),
            axis_sd_floor: 0.0,
            skill_mode: SkillMode::Frame,
            k_rot: 0.0,
            orientation_gains: None,
            orientation_map: true,
        }
    }
}

/// How the one skill follows each demo's start and goal (method.md
/// section 11).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SkillMode {
    /// Frame-independent: the smallest rotation between displacements
    /// times the ratio of their lengths (section 10's `frame` scaling).
    #[default]
    Frame,
    /// The paper's per-axis factors (section 10's `paper` scaling).
    PerAxis,
    /// No map: the demos are assumed to share one absolute forcing term.
    None,
}

impl SkillMode {
    /// Every mode, in the order menus list them.
    pub const ALL: [Self; 3] = [Self::Frame, Self::PerAxis, Self::None];

    /// Its name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::Frame => "frame",
            Self::PerAxis => "per-axis",
            Self::None => "none",
        }
    }

    /// The generalisation it assumes, in words.
    pub fn assumes(self) -> &'static str {
        match self {
            Self::Frame => "the forcing term turns and scales with the goal (frame-independent)",
            Self::PerAxis => "the forcing term scales per axis with the goal (the paper's factor)",
            Self::None => "the forcing term stays the same whatever the goal (no spatial scaling)",
        }
    }

    /// The scaling of section 10 it maps with (`None` for the identity).
    pub(crate) fn scaling(self) -> Option<Scaling> {
        match self {
            Self::Frame => Some(Scaling::Frame),
            Self::PerAxis => Some(Scaling::Paper),
            Self::None => None,
        }
    }
}

impl std::str::FromStr for SkillMode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown skill mode {s:?}: frame, per-axis or none"))
    }
}
