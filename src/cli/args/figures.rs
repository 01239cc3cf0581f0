//! The figures' arguments: what `sweep` computes and `plot` draws, each figure taking only the
//! flags that mean something to it, and where a figure goes.

use super::*;

#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(subcommand)]
    pub figure: SweepFigure,
}

/// What `sweep` computes: each takes only the flags that mean something to it.
#[derive(Subcommand, Debug)]
pub enum SweepFigure {
    /// Fig. 5: v_e over phi for each --xi0, as CSV `xi0,phi,v_escape`.
    Fig5(Fig5Args),
    /// Fig. 6: final rest xi over xi0 in [0, --xi0-max] for release at rest in the lab, as CSV
    /// `xi0,outcome,xi,angle`.
    Fig6(Fig6Args),
    /// The explorer's outcome map: stuck or escaped over (phi, v0) at one --xi0, as CSV
    /// `phi,v0,outcome,xi,angle`.
    Map(MapArgs),
    /// The appendix's body against the point: one release, the two-mass body of each
    /// --lengths run to rest, as CSV `length,l_over_r,outcome,xi,xi_point,xi_error,tau,tau_point`
    /// (r the point's rest radius): the appendix's "L ≪ r" as a number.
    Body(BodySweepArgs),
}

#[derive(Args, Debug)]
pub struct BodySweepArgs {
    /// Release radius [default: case A's 0.5].
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// Direction of the initial velocity, table frame, rad [default: case A's π].
    #[arg(long, default_value_t = std::f64::consts::PI, allow_hyphen_values = true)]
    pub phi: f64,
    /// Initial speed relative to the table [default: case A's 1].
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub v0: f64,
    /// velocity, table-rest or lab-rest.
    #[arg(long, default_value = "velocity", value_parser = variant::<Release>())]
    pub release: Release,
    /// The body lengths L (units of R_max).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values = ["1e-6", "1e-4", "1e-3", "3e-3", "1e-2", "3e-2", "0.1", "0.3"])]
    pub lengths: Vec<f64>,
    /// The rod's angle at release (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub body_angle: f64,
    /// Stop a run at this time if it has neither stuck nor escaped.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
    #[command(flatten)]
    pub out: OutArg,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct Fig5Args {
    #[command(flatten)]
    pub out: OutArg,
    #[command(flatten)]
    pub data: Fig5Data,
}

/// What Fig. 5 is computed from (`sweep fig5`, `plot fig5`).
#[derive(Args, Debug)]
pub struct Fig5Data {
    /// Release radii.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [0.8, 0.5, 0.2, 0.001])]
    pub xi0: Vec<f64>,
    /// Number of angles phi in [0, 2π).
    #[arg(long, default_value_t = 72)]
    pub points: usize,
    /// Width of the final bracket on each escape speed.
    #[arg(long = "vtol", default_value = "1e-6", allow_hyphen_values = true)]
    pub vtol: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct Fig6Args {
    #[command(flatten)]
    pub out: OutArg,
    #[command(flatten)]
    pub data: Fig6Data,
}

/// What Fig. 6 is computed from (`sweep fig6`, `plot fig6`).
#[derive(Args, Debug)]
pub struct Fig6Data {
    /// Number of release radii in [0, --xi0-max].
    #[arg(long, default_value_t = 72)]
    pub points: usize,
    /// Largest release radius.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub xi0_max: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct MapArgs {
    #[command(flatten)]
    pub out: OutArg,
    #[command(flatten)]
    pub data: MapData,
}

/// What the outcome map is computed from (`sweep map`, `plot map`).
#[derive(Args, Debug)]
pub struct MapData {
    /// The release radius [default: 0.5, as `run` and `escape`].
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// How phi and v0 are meant: velocity or table-rest, the speed relative to the table;
    /// lab-rest, the lab velocity (thrown from the lab, u0 = v − Ω×r).
    #[arg(long, default_value = "velocity", value_parser = variant::<Release>())]
    pub release: Release,
    /// Number of angles phi in [0, 2π).
    #[arg(long, default_value_t = 72)]
    pub phi_points: usize,
    /// Number of speeds v0 in (0, --v0-max].
    #[arg(long, default_value_t = 60)]
    pub v0_points: usize,
    /// Largest v0 [default: 1.3 × the largest v_e over phi (outside xi = 1, the top of the sticking window), plus xi0 for lab-rest].
    #[arg(long, allow_hyphen_values = true)]
    pub v0_max: Option<f64>,
    /// Width of the bracket on the escape speeds that set the default --v0-max.
    #[arg(long = "vtol", default_value = "1e-6", allow_hyphen_values = true)]
    pub vtol: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct OutArg {
    /// Write the CSV here instead of stdout (atomically; an existing file is kept unless
    /// --force).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace --out if it exists (never a file this command reads).
    #[arg(long, requires = "out")]
    pub force: bool,
}

#[derive(Args, Debug)]
pub struct PlotArgs {
    #[command(subcommand)]
    pub figure: PlotFigure,
}

/// What `plot` draws: each takes only the flags that mean something to it.
#[derive(Subcommand, Debug)]
pub enum PlotFigure {
    /// Fig. 5: v_e over phi, one curve per --xi0.
    Fig5 {
        #[command(flatten)]
        svg: SvgOut,
        #[command(flatten)]
        data: Fig5Data,
    },
    /// Fig. 6: final rest xi over xi0 for release at rest in the lab, with xi0c marked.
    Fig6 {
        #[command(flatten)]
        svg: SvgOut,
        #[command(flatten)]
        data: Fig6Data,
    },
    /// The outcome map over (phi, v0) at one --xi0, v_e(phi) drawn over it.
    Map {
        #[command(flatten)]
        svg: SvgOut,
        #[command(flatten)]
        data: MapData,
    },
    /// Runs' paths in the lab or the rotating frame (one per --scene and --method), each with
    /// its initial velocity, and the rim xi = 1.
    Trajectory {
        #[command(flatten)]
        run: PlotRun,
        /// The frame the path is drawn in.
        #[arg(long, default_value = "lab", value_parser = variant::<Frame>())]
        frame: Frame,
        #[command(flatten)]
        svg: SvgOut,
    },
    /// One run's xi, theta', |u| and energy against tau (the explorer's time plots).
    Time {
        #[command(flatten)]
        run: PlotRun,
        #[command(flatten)]
        svg: SvgOut,
    },
}

/// The runs a trajectory or time figure shows: scenes, their releases changed by the flags.
#[derive(Args, Debug)]
pub struct PlotRun {
    /// A preset (A, B, C, D, fig1, fig2) or a .toml scene file: its release and integrator.
    /// Repeated, a trajectory draws each (the time plots take one).
    #[arg(long, default_values_t = ["C".to_string()], value_name = "NAME|PATH",
        value_parser = NameOrPath::plot_scenes(), hide_possible_values = true)]
    pub scene: Vec<String>,
    /// The integrator, instead of the scene's, at its default step or tolerance (rk2-raw: the
    /// paper's scheme). Repeated, a trajectory draws each scene with each.
    #[arg(long, value_parser = variant::<Method>())]
    pub method: Vec<Method>,
    /// Release radius xi0, instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub xi0: Option<f64>,
    /// Direction of the initial velocity (rad), instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub phi: Option<f64>,
    /// Initial speed relative to the table, instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub v0: Option<f64>,
    /// How it is released, instead of the scene's: velocity, table-rest or lab-rest.
    #[arg(long, value_parser = variant::<Release>())]
    pub release: Option<Release>,
    /// Draw up to this time if the particle has neither stuck nor escaped far.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
}

/// Where a figure goes.
#[derive(Args, Debug)]
pub struct SvgOut {
    /// The SVG file to write (atomically; an existing file is kept unless --force).
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,
    /// Replace --out if it exists (never a file this command reads).
    #[arg(long)]
    pub force: bool,
}
