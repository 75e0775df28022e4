//! The command line: every subcommand and its options (clap), and how the options map to
//! the library's settings.

use clap::{Args, Parser, Subcommand, ValueEnum};
use eom_model::Method;
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "eom",
    version,
    about = "Linearized equations of motion of multibody systems: analyse, sweep, generate code",
    long_about = "Linearized equations of motion of multibody systems with symbolic parameters.\n\n\
        eom builds a built-in model (see `eom list`), reduces it to a state-space model \
        ẋ = A x + B u, y = C x + D u, and analyses it: modes, what the sensors see, \
        steady-state gains, zeros, frequency response, stability over a parameter range. \
        It can also compile the symbolic model into a Rust module.",
    after_help = "Examples:\n  \
        eom list\n  \
        eom analyze shimmy --set u=1\n  \
        eom analyze bicycle --set v=5 --format json\n  \
        eom analyze quarter_car --freq --freq-range 0.1:100 --points 50\n  \
        eom analyze quarter_car --freq-range 0.1:100 --plot bode.svg --plot-poles poles.svg\n  \
        eom sweep bicycle --param v=0:10:101\n  \
        eom sweep bicycle --param v=0:10:201 --plot bicycle-v.svg\n  \
        eom sweep shimmy --compare shimmy_wing --param x=0:1:201 --plot fin.svg\n  \
        eom aero wing.avl --alpha 2\n  \
        eom codegen bicycle -o bicycle.rs --f32 --no-std\n\n\
        Exit codes: 0 success, 2 unknown model/parameter or malformed argument, 1 other failures."
)]
pub(crate) struct Cli {
    /// No progress bars (they are drawn only when standard error is a terminal anyway)
    #[arg(long, global = true)]
    pub(crate) quiet: bool,
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// List the built-in models with their parameters (defaults, units, allowed values)
    List {
        /// Output format
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Analyse a model at one point: modes, minimal realization, gains, zeros, frequency response
    #[command(long_about = "Analyse a model at one point.\n\n\
        Prints every eigenvalue of the state-space model with natural frequency (Hz), damping \
        ratio, time constant, damped period and stability — real poles show their corner \
        frequency, zero (rigid-body/integrator) modes are labelled; then the modes seen from \
        the inputs and outputs (minimal realization) with a note for every mode it removes \
        (uncontrollable or unobservable, and whether it is unstable); steady-state gains, with \
        integrating pairs reported as such; transmission zeros; warnings of the linearization.\n\n\
        --plot FILE.svg draws a Bode plot (magnitude in dB, unwrapped phase in degrees, one \
        curve per output/input pair); --plot-poles FILE.svg draws the poles and zeros in the \
        complex plane, the modes seen from the inputs and outputs marked apart from the hidden \
        ones.")]
    Analyze(AnalyzeArgs),
    /// Sweep one parameter: eigenvalue branches, stability boundaries, stable intervals
    #[command(long_about = "Sweep one parameter over an equally spaced grid.\n\n\
        The model is reduced symbolically once and its compiled state matrix is evaluated at \
        every value in parallel; values outside the validity region of the symbolic reduction \
        are evaluated by the robust (SVD) path instead, and reported. Eigenvalues are tracked \
        as continuous branches; identically zero branches (a vehicle's lateral position and \
        heading) are neutral and excluded from stability; stability boundaries are located to \
        1e-10 in the parameter; stable intervals are listed.\n\n\
        --plot FILE.svg draws the real parts (top) and damped frequencies |Im λ|/2π (bottom) \
        of the branches over the parameter, with the stable intervals shaded and the \
        boundaries as dashed lines.")]
    Sweep(SweepArgs),
    /// Generate a Rust module that evaluates the model's state-space matrices
    #[command(
        long_about = "Generate a Rust module that evaluates A, B, C, D (and the map to \
        the bodies' coordinates) of the symbolic model for any parameter values, checking the \
        validity region of the symbolic reduction. The file holds one `pub mod MODEL { … }`; \
        include it with `include!`."
    )]
    Codegen(CodegenArgs),
    /// Reduce a model for a controller: Hankel singular values, the error bound per order,
    /// the error measured on a frequency grid, the modes kept
    #[command(
        long_about = "Reduce a model to the dynamics that matter, with its error.\n\n\
        The modes a reduction must not touch — structural zeros (a vehicle's position and \
        heading), other zero, marginal and unstable modes — are split off and kept whole; the \
        stable rest is reduced: --method balanced (square-root balanced truncation, the \
        default), matchdc (its singular perturbation form: the steady-state gain kept exactly) \
        or modal (the modes in --band LOW:HIGH Hz, or the slowest ones, kept with their \
        eigenvalues). Prints the Hankel singular values of the stable part with the bound \
        2·Σσ on ‖G − G_r‖∞ beyond each order, the error measured on a frequency grid and at \
        DC, the modes of the reduced model with the full model's eigenvalue each stands for, \
        and (with --format json) the reduced A, B, C, D. --order R sets the states in all, \
        --tol E the largest bound (in the units of G); by default the bound is kept below \
        1e-3 σ₁. --plot FILE.svg draws the singular values and the bound per order."
    )]
    Reduce(ReduceArgs),
    /// Show the model in closed form: A, B, C, D, the characteristic polynomial, stability
    /// conditions and transfer functions
    #[command(long_about = "Show the model in closed form.\n\n\
        Prints A, B, C, D as simplified expressions of the parameters (structural zeros as \
        zeros), the characteristic polynomial det(sI − A) with its exact common factors divided \
        out, and for two-state models the natural frequency and damping ratio. --stability adds \
        the Hurwitz (Liénard–Chipart) conditions, each as `expression > 0` with the factors \
        whose sign the parameters' declared ranges fix divided out; --solve-for NAME solves \
        them for a parameter where they are of degree ≤ 2 in it; --transfer adds the transfer \
        function of every output/input pair. --set NAME=VALUE substitutes exact values first, \
        so that only the parameters being explored stay symbolic.")]
    Symbolic(SymbolicArgs),
    /// Validate a model (a file, or a built-in) and summarise it: bodies, items, degrees of
    /// freedom, constraints, states
    Check {
        /// Model file (or built-in model name)
        #[arg(value_name = "FILE")]
        model: String,
        /// Output format
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Write a model (a built-in, or a file, normalised) as a model file
    Export {
        /// Model name (see `eom list`) or model file
        #[arg(value_name = "MODEL")]
        model: String,
        /// Set a parameter's value (repeatable)
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Output file (default: standard output)
        #[arg(short, long, value_name = "FILE.toml")]
        output: Option<PathBuf>,
    },
    /// Show the stability derivatives of a wing: AVL geometry (.avl, by the vortex lattice) or
    /// AVL output (.sb body axes, .st stability axes)
    #[command(long_about = "Show the stability derivatives of a wing.\n\n\
        Reads an AVL geometry file (.avl), solved by eom's vortex lattice at the angle of \
        attack --alpha, or a derivative file written by AVL itself (.sb: body axes, the one to \
        prefer; .st: stability axes, from which the u column cannot be recovered). Prints the \
        36 body-axis derivatives by AVL's names (CXu … Cnr, AVL's standard axes x forward, \
        y right, z down) and the dimensional 6×6 ∂F/∂x at the density --rho and airspeed \
        --speed: the negative of the damping block a wing item adds.")]
    Aero(AeroArgs),
    /// Write one self-contained HTML page about a model: parameters and items, a picture, the
    /// modes with their shapes, gains, zeros, Bode and time responses, a sweep, closed forms
    #[command(
        long_about = "Write one self-contained HTML page about a model (no network, \
        plots inline as SVG): the parameters and items, a picture of the model from its \
        geometry, the modes table and every mode's shape (animated), the modes seen from the \
        inputs and outputs, steady-state gains, transmission zeros, the Bode plot, step, \
        impulse and free responses, with --sweep the eigenvalues over a parameter with the \
        stability boundaries and the root locus, and for small models the closed forms \
        (characteristic polynomial, ωn and ζ, stability conditions, transfer functions) in \
        MathML with their LaTeX beside."
    )]
    Report(ReportArgs),
    /// Benchmarks on this machine: `accuracy`, the time and the eigenvalue error of every way
    /// eom offers to get eigenvalues; `throughput`, points per second of a parameter sweep;
    /// `stress`, the map of where each method fails
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Print a commented starter model file (redirect it into NAME.toml)
    New {
        /// The model's name
        #[arg(value_name = "NAME")]
        name: String,
    },
}

#[derive(Subcommand, Debug)]
pub(crate) enum BenchCommand {
    /// Work precision: for each model and each way to get its eigenvalues (numeric, robust,
    /// symbolic on the tape, generated f64, f32 and egg-simplified code), the time per state
    /// matrix and the eigenvalues' error against a double-double reference (and the published
    /// benchmark for the bicycle)
    #[command(
        long_about = "Work precision of every way eom offers to get eigenvalues.\n\n\
        For each model, at random parameter points within ±20 % of nominal: the median time to \
        get the state matrix A (numeric and robust reductions, the symbolic reduction evaluated \
        on the tape, and the generated Rust code compiled into this binary in f64, f32 and after \
        the egg pass), the largest entry-wise relative error of A and the largest relative \
        error of the eigenvalues against a double-double reference of the same model at the \
        same point; for the bicycle also against the published benchmark eigenvalues. Then the \
        rounding error of the entries of A and B as the tape and the generated code compute \
        them, against a double-double evaluation of the same formulas at --entry-points random \
        points (entry-wise, and row-scaled: relative to the largest entry of the row of [A B], \
        the measure by which bench/pydy/accuracy.py measures PyDy's C). Prints the Markdown \
        tables; with -o DIR also writes work_precision.csv, work_precision.md, \
        generated_entries.csv and the chart work_precision.svg (log error against log time, \
        one panel per model)."
    )]
    Accuracy(BenchAccuracyArgs),
    /// Throughput: a sweep of random parameter points of the bicycle through its generated
    /// f64 code and the eigenvalues, in parallel; points per second in total and per thread
    #[command(long_about = "Throughput of a parameter sweep on this machine.\n\n\
        The bicycle's generated f64 code (eval_ab, compiled into this binary) and the \
        eigenvalues of its A at N random parameter points (all 27 parameters within ±20 % of \
        nominal, the speed too, so both stable and unstable points occur; point k depends only \
        on the seed and k), on T threads with rayon. Prints the wall time, the points per \
        second in total and per thread, the thread time per point of drawing the point, of the \
        generated code and of the eigenvalues (by the wall clock, and on Linux by the threads' \
        CPU time, with points per CPU second: what a core costs when the machine is shared), \
        and what the sweep found: failures, the stable points and the range of the largest \
        real part of the non-zero eigenvalues. A second pass times the generated stability \
        verdict without eigenvalues at the same points and counts its undecided points and \
        any disagreement with the eigenvalues.")]
    Throughput(BenchThroughputArgs),
    /// The failure map: sweeps into the regions where methods break (speed to 0 with
    /// nonholonomic contacts, extreme stiffness ratios, a nearly massless body, coalescing
    /// eigenvalues, far from the symbolic nominal point, geometric offsets, redundant and nearly
    /// redundant constraints), each method at each point classed accurate, reported failure or
    /// silently wrong
    #[command(
        long_about = "The failure map of every way eom offers to get eigenvalues.\n\n\
        Each region sweeps one parameter of a model into a range where methods break. At every \
        point the numeric and robust reductions, the symbolic reduction formed at the region's \
        nominal point (evaluated on the tape) and, for the built-in models whose code is \
        compiled in, the generated f64 code are each classed: accurate (eigenvalues within 1e-6 \
        relative of the reference, an eigenvalue below 1e-6 of the spectral radius against that \
        floor, and the same stability verdict), reported failure (an error, or a warning that \
        the result is doubtful) or silently wrong (neither). References: a double-double \
        evaluation of the model's symbolic reduction formed at the point, or a closed form. \
        Prints the table of counts; with -o DIR also writes stress.csv (every cell), \
        stress_counts.csv, stress.md and the map stress.svg. See docs/stress.md."
    )]
    Stress(BenchStressArgs),
}

#[derive(Args, Debug)]
pub(crate) struct BenchThroughputArgs {
    /// Random parameter points
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    pub(crate) points: usize,
    /// Worker threads (default: the machine's available parallelism)
    #[arg(long, value_name = "T")]
    pub(crate) threads: Option<usize>,
}

#[derive(Args, Debug)]
pub(crate) struct BenchStressArgs {
    /// The reduced grid (a few points per region; what CI runs)
    #[arg(long)]
    pub(crate) quick: bool,
    /// Output directory for the CSVs, the Markdown table and the SVG map (created if missing)
    #[arg(short, long, value_name = "DIR")]
    pub(crate) output: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub(crate) struct BenchAccuracyArgs {
    /// Models (default: all of the benchmark's: smd, shimmy, bicycle, quarter_car, top,
    /// chain50, chainp50, smd_wing, shimmy_wing)
    #[arg(value_name = "MODEL")]
    pub(crate) models: Vec<String>,
    /// Random parameter points per model (models with more than 40 states use at most 4)
    #[arg(long, value_name = "N", default_value_t = 64)]
    pub(crate) points: usize,
    /// Minimum time spent timing each method, in milliseconds
    #[arg(long, value_name = "MS", default_value_t = 200)]
    pub(crate) min_time: u64,
    /// Random parameter points of the entry errors of A and B (the tape's and the generated
    /// code's, against double-double)
    #[arg(long, value_name = "N", default_value_t = 1024)]
    pub(crate) entry_points: usize,
    /// Output directory for the CSVs, the Markdown table and the SVG chart (created if missing)
    #[arg(short, long, value_name = "DIR")]
    pub(crate) output: Option<PathBuf>,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// Human-readable tables
    Text,
    /// Pretty-printed JSON
    Json,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SweepFormat {
    /// Human-readable table with boundaries and stable intervals
    Text,
    /// Pretty-printed JSON
    Json,
    /// One row per value: value, re1, im1, … (eigenvalues in branch order)
    Csv,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum MethodArg {
    /// Reduce symbolically with pivots chosen at the model's defaults, evaluate at the point
    /// (fails outside the validity region of those pivots)
    Symbolic,
    /// The same elimination in f64 at the point, pivots chosen there
    Numeric,
    /// Orthonormal (SVD) complements and descriptor reduction
    Robust,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::Symbolic => Method::Symbolic,
            MethodArg::Numeric => Method::Numeric,
            MethodArg::Robust => Method::Robust,
        }
    }
}

#[derive(Args, Debug)]
pub(crate) struct AnalyzeArgs {
    /// Model name (see `eom list`; chains as chainN, e.g. chain50) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// Reduction method
    #[arg(long, value_enum, default_value_t = MethodArg::Numeric)]
    pub(crate) method: MethodArg,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Also compute the frequency response of every output/input pair
    #[arg(long)]
    pub(crate) freq: bool,
    /// Frequency range in Hz for the response (implies --freq; default: whole decades around
    /// the modes)
    #[arg(long, value_name = "LOW:HIGH")]
    pub(crate) freq_range: Option<String>,
    /// Number of logarithmically spaced frequencies (implies --freq; default: 200 per decade)
    #[arg(long, value_name = "N")]
    pub(crate) points: Option<usize>,
    /// Draw a Bode plot of every output/input pair into an SVG file (implies --freq)
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot: Option<PathBuf>,
    /// Draw the poles and transmission zeros in the complex plane into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot_poles: Option<PathBuf>,
    /// Eigenvalue sensitivities ∂λ/∂p to every parameter (exact ∂A/∂p from the symbolic
    /// model, numeric eigenvectors; defective eigenvalues are flagged, not given a number)
    #[arg(long)]
    pub(crate) sensitivity: bool,
    /// Draw the unit step and impulse responses of every output to every input into an SVG
    /// file (the time span from the slowest mode)
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot_step: Option<PathBuf>,
    /// Draw the free response of every output started in one mode (x₀ = Re v; --mode K,
    /// default the least damped oscillatory mode) into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot_initial: Option<PathBuf>,
    /// Draw the mode shapes from the model's geometry (the extremes of the motion, the
    /// centres of rotation, animated in a browser) into an SVG file: every mode that moves a
    /// body, or mode K with --mode K
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot_modes: Option<PathBuf>,
    /// The mode of --plot-initial and --plot-modes: its number in the modes table
    #[arg(long, value_name = "K")]
    pub(crate) mode: Option<usize>,
    /// Write the numeric A, B, C, D with the state, input and output names: NumPy .npz
    /// (numpy.load) or MATLAB .mat (load, scipy.io.loadmat), by the extension
    #[arg(long, value_name = "FILE.npz|FILE.mat")]
    pub(crate) matrices: Option<PathBuf>,
    /// Add a reduced model (as `eom reduce`): R states in all, or without R the smallest
    /// order whose bound 2·Σσ is below 1e-3 σ₁
    #[arg(long, value_name = "R", num_args = 0..=1, default_missing_value = "default")]
    pub(crate) reduce: Option<String>,
    /// How --reduce reduces the stable part
    #[arg(long, value_enum, requires = "reduce")]
    pub(crate) reduce_method: Option<ReduceMethodArg>,
}

#[derive(Args, Debug)]
pub(crate) struct SweepArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// The swept parameter and its grid: COUNT equally spaced values from START to STOP
    #[arg(long, value_name = "NAME=START:STOP:COUNT", required = true)]
    pub(crate) param: String,
    /// Set another parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = SweepFormat::Text)]
    pub(crate) format: SweepFormat,
    /// Draw the eigenvalue branches (real parts, damped frequencies), the stability
    /// boundaries and the stable intervals into an SVG file (needs COUNT ≥ 2)
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot: Option<PathBuf>,
    /// Sweep a second model over the same grid (same --set values) and report it too; with
    /// --plot, draw both in one plot
    #[arg(long, value_name = "MODEL")]
    pub(crate) compare: Option<String>,
    /// With --plot: add a panel of the real parts near zero, |Re λ| ≤ HALF in 1/s (`auto`,
    /// the default: 5 % of the largest |Re λ| drawn)
    #[arg(long, value_name = "HALF", num_args = 0..=1, default_missing_value = "auto")]
    pub(crate) zoom: Option<String>,
    /// Draw the root locus (the eigenvalues' paths in the complex plane, the parameter
    /// labelled along them, the crossings of the imaginary axis marked) into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot_locus: Option<PathBuf>,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ReduceMethodArg {
    /// Square-root balanced truncation (bound 2·Σσ)
    Balanced,
    /// Balanced singular perturbation: the same bound, the steady-state gain matched
    Matchdc,
    /// Modal truncation: the modes in --band (or the slowest) kept exactly
    Modal,
}

#[derive(Args, Debug)]
pub(crate) struct ReduceArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// States of the reduced model in all (the kept ones included)
    #[arg(long, value_name = "R", conflicts_with = "tol")]
    pub(crate) order: Option<usize>,
    /// Largest error bound 2·Σσ (units of G; balanced and matchdc)
    #[arg(long, value_name = "E")]
    pub(crate) tol: Option<f64>,
    /// How the stable part is reduced
    #[arg(long, value_enum, default_value_t = ReduceMethodArg::Balanced)]
    pub(crate) method: ReduceMethodArg,
    /// Modal truncation: keep the stable modes with natural frequency in LOW:HIGH Hz
    #[arg(long, value_name = "LOW:HIGH")]
    pub(crate) band: Option<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Draw the Hankel singular values and the bound per order into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    pub(crate) plot: Option<PathBuf>,
    /// Write the reduced A, B, C, D with the state, input and output names: NumPy .npz
    /// (numpy.load) or MATLAB .mat (load, scipy.io.loadmat), by the extension
    #[arg(long, value_name = "FILE.npz|FILE.mat")]
    pub(crate) matrices: Option<PathBuf>,
    /// Linearization method
    #[arg(long = "linearize", value_enum, default_value_t = MethodArg::Numeric)]
    pub(crate) linearize: MethodArg,
}

#[derive(Args, Debug)]
pub(crate) struct ReportArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// Add a sweep of one parameter: eigenvalues over it, its boundaries, the root locus
    #[arg(long, value_name = "NAME=START:STOP:COUNT")]
    pub(crate) sweep: Option<String>,
    /// Output directory (created if missing, when its parent exists); the page is
    /// DIR/MODEL.html
    #[arg(short, long, value_name = "DIR")]
    pub(crate) output: PathBuf,
}

#[derive(Args, Debug)]
pub(crate) struct AeroArgs {
    /// AVL geometry (.avl) or AVL derivative file (.sb, .st)
    #[arg(value_name = "FILE")]
    pub(crate) file: String,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Angle of attack of the trim state in degrees (.avl only; default 0)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub(crate) alpha: Option<f64>,
    /// Moment reference point Xref,Yref,Zref in AVL's geometry axes (x aft, y right, z up;
    /// .avl only; default: the file's)
    #[arg(long = "ref", value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) reference: Option<String>,
    /// Air density of the dimensional matrix [kg/m^3]
    #[arg(long, value_name = "RHO", default_value_t = 1.225)]
    pub(crate) rho: f64,
    /// Airspeed of the dimensional matrix [m/s]
    #[arg(long, value_name = "V", default_value_t = 10.0)]
    pub(crate) speed: f64,
}

#[derive(Args, Debug)]
pub(crate) struct CodegenArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// Output file
    #[arg(short, long, value_name = "FILE.rs")]
    pub(crate) output: PathBuf,
    /// Generate f32 code (default f64)
    #[arg(long)]
    pub(crate) f32: bool,
    /// Code for #![no_std] targets: elementary functions from the `libm` crate
    #[arg(long)]
    pub(crate) no_std: bool,
    /// Simplify the expressions first (bounded e-graph rewriting; used only when it gives
    /// fewer operations and is estimated faster)
    #[arg(long)]
    pub(crate) simplify: bool,
    /// Simplify, and use the result whenever it has fewer operations, even when estimated
    /// slower (factoring can remove cancellations: more accurate, maybe slower)
    #[arg(long)]
    pub(crate) simplify_always: bool,
    /// Nominal parameter value (repeatable): where the pivots are chosen, and the default of
    /// the generated `Params::NOMINAL`
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// Name of the generated module (default: from the model name)
    #[arg(long, value_name = "NAME")]
    pub(crate) module: Option<String>,
    /// Also emit the characteristic polynomial, the Liénard–Chipart conditions with their
    /// rounding-error bounds and `stability(p)`, the verdict without eigenvalues (f64 only)
    #[arg(long)]
    pub(crate) stability: bool,
    /// Generate a reduced model of R states: balanced truncation at the nominal point, its
    /// bases applied to A(p), B(p), C(p) (see `eom reduce`)
    #[arg(long, value_name = "R")]
    pub(crate) reduce: Option<usize>,
    /// With --reduce: modal instead of balanced truncation (the R − kept slowest modes)
    #[arg(long, requires = "reduce")]
    pub(crate) reduce_modal: bool,
    /// Also generate `eval_discrete`: the zero-order-hold Ad = e^{A h}, Bd = ∫e^{A t}dt B at a
    /// sample time h (no allocation)
    #[arg(long)]
    pub(crate) discrete: bool,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SymbolicFormat {
    /// Plain text for a terminal
    Text,
    /// LaTeX (an align* block)
    Latex,
    /// JSON, with expressions in the syntax `eom` parses
    Json,
}

#[derive(Args, Debug)]
pub(crate) struct SymbolicArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    pub(crate) model: String,
    /// Substitute a parameter by an exact value (repeatable; `0.21` is 21/100)
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub(crate) set: Vec<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = SymbolicFormat::Text)]
    pub(crate) format: SymbolicFormat,
    /// Add the stability conditions
    #[arg(long)]
    pub(crate) stability: bool,
    /// Solve the stability conditions for this parameter (implies --stability)
    #[arg(long, value_name = "NAME")]
    pub(crate) solve_for: Option<String>,
    /// Add the transfer function of every output/input pair
    #[arg(long)]
    pub(crate) transfer: bool,
    /// Largest number of states for the closed forms (default 8; the work grows as n·2ⁿ)
    #[arg(long, value_name = "N")]
    pub(crate) max_states: Option<usize>,
}
