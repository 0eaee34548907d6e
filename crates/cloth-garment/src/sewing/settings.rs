//! How the sewing stage runs.

use cloth_core::{ParamError, RestCriteria, SelfCollision, SolverSettings};
use serde::{Deserialize, Serialize};

/// Settings of the sewing stage.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SewingSettings {
    /// Time step, s. The seams close no faster than the closing speed, 12 mm a step at a
    /// 25th of a second, under a cell: the step of 1/50 s took twice the steps to the same
    /// sewn garment (rand_1_014: 109 steps against 56).
    pub time_step: f64,
    /// The seams are welded when every pair is closer than this, m.
    pub gap_tolerance: f64,
    /// The sewing fails after this many steps.
    pub max_steps: u64,
    /// The full pull per seam pair is the fabric's tension at this strain times the
    /// pair's share of seam: the seams can stretch the cloth this much, and no more.
    pub pull_strain: f64,
    /// The pull grows linearly to full strength over this time, s. At 0.2 s it yanked the
    /// seam particles across the gap faster than the panels could follow (the main job's
    /// cloth at 3 m/s in its second step, cells stretched fivefold), and with the cloth
    /// kept from passing through itself the flailing panels crumpled where they met, for
    /// the drape to smooth out over hundreds of steps; over a second they glide together.
    pub ramp_time: f64,
    /// Within this gap (m) the pull falls linearly to zero, so pairs settle instead of
    /// chattering; beyond it the pull is constant.
    pub reach: f64,
    /// Air drag while sewing, kg/(m^2 s): panels glide into place instead of flying.
    pub drag: f64,
    /// The fastest a seam pair closes, m/s, if set: each pair then has a dashpot that
    /// takes the whole pull at this closing speed. Drag alone does not bound it, as it
    /// acts on a panel's area and the pull on its seam's length: GarmentCode places panels
    /// up to half a metre from where they are sewn, and a hooded top's corners crossed
    /// that at 6 m/s and crashed, crumpled, into the other panels and the head (at 0.3 m/s
    /// they glide). It also keeps the light particles of GarmentCode's millimetre-long
    /// outline edges, free to swing where a gather leaves the cloth slack, from being
    /// thrown: without it they left at 2 m/s in the first step. 0.3 m/s by default (`None`,
    /// from Rust, turns it off).
    pub closing_speed: Option<f64>,
    /// How far below where it was placed a panel not dressing the legs may sink until the
    /// seams first stall, m, if set. Gravity is off, but the seams' pull swings panels
    /// placed out round the body down about their edges sewn first: GarmentCode's tops
    /// (rand_1_094, 048) had their shoulders and sleeves' tops 7 to 12 cm lower before
    /// they touched the body to be held by its friction, and their sleeves then closed
    /// round the arms' undersides with the arm between their seams' sides. 1 cm by
    /// default (`None`, from Rust, holds nothing).
    pub height_slack: Option<f64>,
    /// The cloth's collision with itself (a scene sets it for all its stages at once, in
    /// its `[self_collision]` table). The particles each seam pulls together, and their
    /// neighbours, are exempt until welded.
    #[serde(skip)]
    pub self_collision: SelfCollision,
}

impl Default for SewingSettings {
    fn default() -> Self {
        Self {
            time_step: 1.0 / 25.0,
            gap_tolerance: 1e-3,
            max_steps: 3000,
            pull_strain: 0.01,
            ramp_time: 1.0,
            reach: 0.0005,
            drag: 5.0,
            closing_speed: Some(0.3),
            height_slack: Some(0.01),
            self_collision: SelfCollision::default(),
        }
    }
}

impl SewingSettings {
    pub fn validate(&self) -> Result<(), ParamError> {
        let positive = |value: f64, name: &'static str, expected: &'static str| {
            ParamError::check(value.is_finite() && value > 0.0, name, value, expected)
        };
        positive(self.time_step, "sewing.time_step", "a positive time step in s")?;
        positive(
            self.gap_tolerance,
            "sewing.gap_tolerance",
            "a positive distance in m",
        )?;
        positive(self.pull_strain, "sewing.pull_strain", "a positive strain")?;
        positive(self.ramp_time, "sewing.ramp_time", "a positive time in s")?;
        positive(self.reach, "sewing.reach", "a positive distance in m")?;
        if let Some(speed) = self.closing_speed {
            positive(speed, "sewing.closing_speed", "a positive speed in m/s")?;
        }
        if let Some(slack) = self.height_slack {
            ParamError::check(
                slack.is_finite() && slack >= 0.0,
                "sewing.height_slack",
                slack,
                "a distance >= 0 in m",
            )?;
        }
        ParamError::check(
            self.drag.is_finite() && self.drag >= 0.0,
            "sewing.drag",
            self.drag,
            "a drag coefficient >= 0 kg/(m^2 s)",
        )?;
        ParamError::check(self.max_steps > 0, "sewing.max_steps", 0.0, "at least one step")?;
        self.self_collision.validate()
    }
}

/// Settings of the draping stage: the implicit integrator with gravity, run until at rest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DrapeSettings {
    /// Time step, s. A garment settling onto a body is slow, quasi-static motion, which
    /// backward Euler follows at steps of a thirtieth of a second as well as at a
    /// sixtieth (the rest state differs by a fraction of a millimetre), in half the steps.
    pub time_step: f64,
    /// The step grows, while the steps go well, up to this, s (see
    /// [`RestCriteria::max_time_step`]; at most the time step: it does not grow). Up to
    /// 0.3 s rather than 0.1, the 42 quickest of GarmentCode's 60 shared designs on its
    /// mean body took 2,450 drape steps rather than 4,120, with the same outcomes, their
    /// rests as far apart (under 8.5 mm at each design's median, up to 7.5 cm on loose
    /// flounces and hoods) as two runs differing only by rounding (up to 6.4 cm);
    /// rand_1_038, a tiered skirt, rests in 210 steps rather than 380, within the 10
    /// minutes it overran.
    pub max_time_step: f64,
    /// At rest when every particle has moved less than this speed, m/s, times the time ...
    /// GarmentCode's rand_1_037 at rest by 6 mm/s (over windows of 10 steps) stopped 50
    /// steps into its drape with its hem 3.5 cm (p99) from where it came to rest 450
    /// steps later; by 2 mm/s, 170 steps in and within 6.5 mm of it.
    pub rest_speed: f64,
    /// ... over a window of this many steps (from end to end: see [`RestCriteria`]) ...
    pub consecutive_steps: u32,
    /// ... all but this fraction of them (see [`RestCriteria::moving_fraction`]). A
    /// garment whose loose front creeps down the body at 5 mm/s, at the rest speed, went
    /// on for 1,100 steps (rand_1_017) and more when every particle had to rest.
    pub moving_fraction: f64,
    /// The drape stops here if not at rest.
    pub max_steps: u64,
    /// Air drag while settling, kg/(m^2 s), where a fabric's own is lower. The presets
    /// carry no damping, and a hanging skirt then sways for seconds; at rest drag does
    /// nothing, so it only shortens the way there.
    pub drag: f64,
    /// The cloth's collision with itself (a scene sets it for all its stages at once).
    #[serde(skip)]
    pub self_collision: SelfCollision,
}

impl Default for DrapeSettings {
    fn default() -> Self {
        Self {
            time_step: 1.0 / 30.0,
            max_time_step: 0.3,
            rest_speed: 2e-3,
            consecutive_steps: 10,
            moving_fraction: 0.01,
            max_steps: 3000,
            drag: 0.5,
            self_collision: SelfCollision::default(),
        }
    }
}

impl DrapeSettings {
    pub fn validate(&self) -> Result<(), ParamError> {
        ParamError::check(
            self.time_step.is_finite() && self.time_step > 0.0,
            "drape.time_step",
            self.time_step,
            "a positive time step in s",
        )?;
        ParamError::check(
            self.max_time_step.is_finite() && self.max_time_step > 0.0,
            "drape.max_time_step",
            self.max_time_step,
            "a positive time step in s",
        )?;
        ParamError::check(
            self.rest_speed.is_finite() && self.rest_speed > 0.0,
            "drape.rest_speed",
            self.rest_speed,
            "a positive speed in m/s",
        )?;
        ParamError::check(
            self.drag.is_finite() && self.drag >= 0.0,
            "drape.drag",
            self.drag,
            "a drag coefficient >= 0 kg/(m^2 s)",
        )?;
        ParamError::check(
            (0.0..1.0).contains(&self.moving_fraction),
            "drape.moving_fraction",
            self.moving_fraction,
            "a fraction in [0, 1)",
        )?;
        self.self_collision.validate()
    }
    /// The solver settings: implicit Euler at the time step, gravity on, the
    /// self-collision, otherwise default.
    pub fn solver(&self) -> SolverSettings {
        SolverSettings {
            time_step: self.time_step,
            self_collision: self.self_collision,
            ..SolverSettings::default()
        }
    }
    /// The source's stopping mechanism in displacement per step.
    pub fn rest(&self) -> RestCriteria {
        RestCriteria {
            max_time_step: (self.max_time_step > self.time_step).then_some(self.max_time_step),
            tolerance: self.rest_speed * self.time_step,
            consecutive_steps: self.consecutive_steps,
            max_steps: self.max_steps,
            moving_fraction: self.moving_fraction,
        }
    }
}
