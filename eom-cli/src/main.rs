//! `eom` — linearized equations of motion of the built-in multibody models: list them,
//! analyse one at a point, sweep a parameter for stability boundaries, generate Rust code.
//!
//! Exit codes: 0 success; 2 unknown model or parameter, malformed argument (the message on
//! standard error lists the valid names); 1 any other failure (e.g. a point outside the
//! validity region of the symbolic reduction with `--method symbolic`).

#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod aero;
mod analyze;
mod analyze_text;
#[cfg(feature = "bench")]
mod bench;
mod check;
mod codegen;
mod error;
mod format;
mod list;
mod matrices;
mod output;
mod params;
mod pictures;
mod plot;
mod preloads;
mod progress;
mod reduce;
mod report;
mod shown_warning;
mod sweep;
mod symbolic;
mod timing;
mod wings;

use crate::analyze::{AnalyzeOptions, FreqRequest};
use crate::codegen::CodegenRequest;
use crate::error::CliError;
use crate::params::{ModelChoice, SweepSpec, parse_freq_range};
use clap::{Args, Parser, Subcommand, ValueEnum};
use eom_model::Method;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
struct Cli {
    /// No progress bars (they are drawn only when standard error is a terminal anyway)
    #[arg(long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
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
enum BenchCommand {
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
struct BenchThroughputArgs {
    /// Random parameter points
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    points: usize,
    /// Worker threads (default: the machine's available parallelism)
    #[arg(long, value_name = "T")]
    threads: Option<usize>,
}

#[derive(Args, Debug)]
struct BenchStressArgs {
    /// The reduced grid (a few points per region; what CI runs)
    #[arg(long)]
    quick: bool,
    /// Output directory for the CSVs, the Markdown table and the SVG map (created if missing)
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct BenchAccuracyArgs {
    /// Models (default: all of the benchmark's: smd, shimmy, bicycle, quarter_car, top,
    /// chain50, chainp50, smd_wing, shimmy_wing)
    #[arg(value_name = "MODEL")]
    models: Vec<String>,
    /// Random parameter points per model (models with more than 40 states use at most 4)
    #[arg(long, value_name = "N", default_value_t = 64)]
    points: usize,
    /// Minimum time spent timing each method, in milliseconds
    #[arg(long, value_name = "MS", default_value_t = 200)]
    min_time: u64,
    /// Random parameter points of the entry errors of A and B (the tape's and the generated
    /// code's, against double-double)
    #[arg(long, value_name = "N", default_value_t = 1024)]
    entry_points: usize,
    /// Output directory for the CSVs, the Markdown table and the SVG chart (created if missing)
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum Format {
    /// Human-readable tables
    Text,
    /// Pretty-printed JSON
    Json,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum SweepFormat {
    /// Human-readable table with boundaries and stable intervals
    Text,
    /// Pretty-printed JSON
    Json,
    /// One row per value: value, re1, im1, … (eigenvalues in branch order)
    Csv,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum MethodArg {
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
struct AnalyzeArgs {
    /// Model name (see `eom list`; chains as chainN, e.g. chain50) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Reduction method
    #[arg(long, value_enum, default_value_t = MethodArg::Numeric)]
    method: MethodArg,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Also compute the frequency response of every output/input pair
    #[arg(long)]
    freq: bool,
    /// Frequency range in Hz for the response (implies --freq; default: whole decades around
    /// the modes)
    #[arg(long, value_name = "LOW:HIGH")]
    freq_range: Option<String>,
    /// Number of logarithmically spaced frequencies (implies --freq; default: 200 per decade)
    #[arg(long, value_name = "N")]
    points: Option<usize>,
    /// Draw a Bode plot of every output/input pair into an SVG file (implies --freq)
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// Draw the poles and transmission zeros in the complex plane into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    plot_poles: Option<PathBuf>,
    /// Eigenvalue sensitivities ∂λ/∂p to every parameter (exact ∂A/∂p from the symbolic
    /// model, numeric eigenvectors; defective eigenvalues are flagged, not given a number)
    #[arg(long)]
    sensitivity: bool,
    /// Draw the unit step and impulse responses of every output to every input into an SVG
    /// file (the time span from the slowest mode)
    #[arg(long, value_name = "FILE.svg")]
    plot_step: Option<PathBuf>,
    /// Draw the free response of every output started in one mode (x₀ = Re v; --mode K,
    /// default the least damped oscillatory mode) into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    plot_initial: Option<PathBuf>,
    /// Draw the mode shapes from the model's geometry (the extremes of the motion, the
    /// centres of rotation, animated in a browser) into an SVG file: every mode that moves a
    /// body, or mode K with --mode K
    #[arg(long, value_name = "FILE.svg")]
    plot_modes: Option<PathBuf>,
    /// The mode of --plot-initial and --plot-modes: its number in the modes table
    #[arg(long, value_name = "K")]
    mode: Option<usize>,
    /// Write the numeric A, B, C, D with the state, input and output names: NumPy .npz
    /// (numpy.load) or MATLAB .mat (load, scipy.io.loadmat), by the extension
    #[arg(long, value_name = "FILE.npz|FILE.mat")]
    matrices: Option<PathBuf>,
    /// Add a reduced model (as `eom reduce`): R states in all, or without R the smallest
    /// order whose bound 2·Σσ is below 1e-3 σ₁
    #[arg(long, value_name = "R", num_args = 0..=1, default_missing_value = "default")]
    reduce: Option<String>,
    /// How --reduce reduces the stable part
    #[arg(long, value_enum, requires = "reduce")]
    reduce_method: Option<ReduceMethodArg>,
}

#[derive(Args, Debug)]
struct SweepArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// The swept parameter and its grid: COUNT equally spaced values from START to STOP
    #[arg(long, value_name = "NAME=START:STOP:COUNT", required = true)]
    param: String,
    /// Set another parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = SweepFormat::Text)]
    format: SweepFormat,
    /// Draw the eigenvalue branches (real parts, damped frequencies), the stability
    /// boundaries and the stable intervals into an SVG file (needs COUNT ≥ 2)
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// Sweep a second model over the same grid (same --set values) and report it too; with
    /// --plot, draw both in one plot
    #[arg(long, value_name = "MODEL")]
    compare: Option<String>,
    /// With --plot: add a panel of the real parts near zero, |Re λ| ≤ HALF in 1/s (`auto`,
    /// the default: 5 % of the largest |Re λ| drawn)
    #[arg(long, value_name = "HALF", num_args = 0..=1, default_missing_value = "auto")]
    zoom: Option<String>,
    /// Draw the root locus (the eigenvalues' paths in the complex plane, the parameter
    /// labelled along them, the crossings of the imaginary axis marked) into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    plot_locus: Option<PathBuf>,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum ReduceMethodArg {
    /// Square-root balanced truncation (bound 2·Σσ)
    Balanced,
    /// Balanced singular perturbation: the same bound, the steady-state gain matched
    Matchdc,
    /// Modal truncation: the modes in --band (or the slowest) kept exactly
    Modal,
}

#[derive(Args, Debug)]
struct ReduceArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// States of the reduced model in all (the kept ones included)
    #[arg(long, value_name = "R", conflicts_with = "tol")]
    order: Option<usize>,
    /// Largest error bound 2·Σσ (units of G; balanced and matchdc)
    #[arg(long, value_name = "E")]
    tol: Option<f64>,
    /// How the stable part is reduced
    #[arg(long, value_enum, default_value_t = ReduceMethodArg::Balanced)]
    method: ReduceMethodArg,
    /// Modal truncation: keep the stable modes with natural frequency in LOW:HIGH Hz
    #[arg(long, value_name = "LOW:HIGH")]
    band: Option<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Draw the Hankel singular values and the bound per order into an SVG file
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// Write the reduced A, B, C, D with the state, input and output names: NumPy .npz
    /// (numpy.load) or MATLAB .mat (load, scipy.io.loadmat), by the extension
    #[arg(long, value_name = "FILE.npz|FILE.mat")]
    matrices: Option<PathBuf>,
    /// Linearization method
    #[arg(long = "linearize", value_enum, default_value_t = MethodArg::Numeric)]
    linearize: MethodArg,
}

#[derive(Args, Debug)]
struct ReportArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// Set a parameter (repeatable); the others keep their defaults
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Add a sweep of one parameter: eigenvalues over it, its boundaries, the root locus
    #[arg(long, value_name = "NAME=START:STOP:COUNT")]
    sweep: Option<String>,
    /// Output directory (created if missing, when its parent exists); the page is
    /// DIR/MODEL.html
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
}

#[derive(Args, Debug)]
struct AeroArgs {
    /// AVL geometry (.avl) or AVL derivative file (.sb, .st)
    #[arg(value_name = "FILE")]
    file: String,
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Angle of attack of the trim state in degrees (.avl only; default 0)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    alpha: Option<f64>,
    /// Moment reference point Xref,Yref,Zref in AVL's geometry axes (x aft, y right, z up;
    /// .avl only; default: the file's)
    #[arg(long = "ref", value_name = "X,Y,Z", allow_hyphen_values = true)]
    reference: Option<String>,
    /// Air density of the dimensional matrix [kg/m^3]
    #[arg(long, value_name = "RHO", default_value_t = 1.225)]
    rho: f64,
    /// Airspeed of the dimensional matrix [m/s]
    #[arg(long, value_name = "V", default_value_t = 10.0)]
    speed: f64,
}

#[derive(Args, Debug)]
struct CodegenArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// Output file
    #[arg(short, long, value_name = "FILE.rs")]
    output: PathBuf,
    /// Generate f32 code (default f64)
    #[arg(long)]
    f32: bool,
    /// Code for #![no_std] targets: elementary functions from the `libm` crate
    #[arg(long)]
    no_std: bool,
    /// Simplify the expressions first (bounded e-graph rewriting; used only when it gives
    /// fewer operations and is estimated faster)
    #[arg(long)]
    simplify: bool,
    /// Simplify, and use the result whenever it has fewer operations, even when estimated
    /// slower (factoring can remove cancellations: more accurate, maybe slower)
    #[arg(long)]
    simplify_always: bool,
    /// Nominal parameter value (repeatable): where the pivots are chosen, and the default of
    /// the generated `Params::NOMINAL`
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Name of the generated module (default: from the model name)
    #[arg(long, value_name = "NAME")]
    module: Option<String>,
    /// Also emit the characteristic polynomial, the Liénard–Chipart conditions with their
    /// rounding-error bounds and `stability(p)`, the verdict without eigenvalues (f64 only)
    #[arg(long)]
    stability: bool,
    /// Generate a reduced model of R states: balanced truncation at the nominal point, its
    /// bases applied to A(p), B(p), C(p) (see `eom reduce`)
    #[arg(long, value_name = "R")]
    reduce: Option<usize>,
    /// With --reduce: modal instead of balanced truncation (the R − kept slowest modes)
    #[arg(long, requires = "reduce")]
    reduce_modal: bool,
    /// Also generate `eval_discrete`: the zero-order-hold Ad = e^{A h}, Bd = ∫e^{A t}dt B at a
    /// sample time h (no allocation)
    #[arg(long)]
    discrete: bool,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum SymbolicFormat {
    /// Plain text for a terminal
    Text,
    /// LaTeX (an align* block)
    Latex,
    /// JSON, with expressions in the syntax `eom` parses
    Json,
}

#[derive(Args, Debug)]
struct SymbolicArgs {
    /// Model name (see `eom list`) or model file (.toml)
    #[arg(value_name = "MODEL")]
    model: String,
    /// Substitute a parameter by an exact value (repeatable; `0.21` is 21/100)
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Output format
    #[arg(long, value_enum, default_value_t = SymbolicFormat::Text)]
    format: SymbolicFormat,
    /// Add the stability conditions
    #[arg(long)]
    stability: bool,
    /// Solve the stability conditions for this parameter (implies --stability)
    #[arg(long, value_name = "NAME")]
    solve_for: Option<String>,
    /// Add the transfer function of every output/input pair
    #[arg(long)]
    transfer: bool,
    /// Largest number of states for the closed forms (default 8; the work grows as n·2ⁿ)
    #[arg(long, value_name = "N")]
    max_states: Option<usize>,
}

/// Where the output goes: standard output, or a note on standard error.
struct Output {
    stdout: String,
    stderr: String,
}

fn json<T: serde::Serialize>(v: &T) -> Result<String, CliError> {
    let mut s = serde_json::to_string_pretty(v)?;
    s.push('\n');
    Ok(s)
}

/// `eom bench …`: the benchmarks' output (notes of written files on `stderr`).
#[cfg(feature = "bench")]
fn run_bench(b: BenchCommand, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    Ok(match b {
        BenchCommand::Accuracy(b) => {
            let req = bench::AccuracyRequest {
                models: b.models,
                points: b.points,
                min_time_ms: b.min_time,
                entry_points: b.entry_points,
                dir: b.output,
            };
            bench::accuracy(&req, quiet, stderr)?
        }
        BenchCommand::Throughput(t) => bench::throughput(t.points, t.threads)?,
        BenchCommand::Stress(b) => {
            let req = bench::StressRequest {
                quick: b.quick,
                dir: b.output,
            };
            bench::stress(&req, quiet, stderr)?
        }
    })
}

/// Without the `bench` feature: `eom bench` says that this build does not include it.
#[cfg(not(feature = "bench"))]
fn run_bench(_: BenchCommand, _: bool, _: &mut String) -> Result<String, CliError> {
    Err(CliError::Unavailable(
        "the benchmarks are not available in this build of eom (built without the cargo \
         feature `bench`, which links the eom-bench crate). Rebuild with \
         `cargo build -p eom-cli --features bench`."
            .into(),
    ))
}

fn run(cli: Cli) -> Result<Output, CliError> {
    let mut stderr = String::new();
    let stdout = match cli.command {
        Command::List { format } => {
            let e = list::entries();
            match format {
                Format::Text => list::to_text(&e),
                Format::Json => json(&e)?,
            }
        }
        Command::Analyze(a) => run_analyze(&a, &mut stderr)?,
        Command::Reduce(r) => run_reduce(&r, &mut stderr)?,
        Command::Sweep(s) if s.compare.is_some() => sweep_compare(&s, cli.quiet, &mut stderr)?,
        Command::Sweep(s) => run_sweep(&s, cli.quiet, &mut stderr)?,
        Command::Report(r) => {
            let choice = ModelChoice::resolve(&r.model)?;
            let overrides = choice.parse_sets(&r.set)?;
            let spec = r
                .sweep
                .as_deref()
                .map(|s| SweepSpec::parse_option("--sweep", s))
                .transpose()?;
            let w = report::write_report(&choice, &overrides, spec.as_ref(), &r.output, cli.quiet)?;
            if w.created_dir {
                stderr.push_str(&format!("created directory {}\n", r.output.display()));
            }
            stderr.push_str(&output::status_line(&w.path, w.written));
            String::new()
        }
        Command::Codegen(c) => {
            let choice = ModelChoice::resolve(&c.model)?;
            let overrides = choice.parse_sets(&c.set)?;
            let req = CodegenRequest {
                f32: c.f32,
                no_std: c.no_std,
                simplify: c.simplify,
                simplify_always: c.simplify_always,
                module: c.module,
                stability: c.stability,
                reduce: c.reduce,
                reduce_modal: c.reduce_modal,
                discrete: c.discrete,
            };
            // The summary is a status: standard error (the output may be `/dev/stdout`).
            stderr.push_str(&codegen::codegen(&choice, &overrides, &req, &c.output)?);
            String::new()
        }
        Command::Check { model, format } => {
            let choice = ModelChoice::resolve(&model)?;
            let r = check::check(&choice)?;
            match format {
                Format::Text => r.to_text(),
                Format::Json => json(&r)?,
            }
        }
        Command::New { name } => check::starter(&name)?,
        Command::Bench(b) => run_bench(b, cli.quiet, &mut stderr)?,
        Command::Export { model, set, output } => {
            let choice = ModelChoice::resolve(&model)?;
            let overrides = choice.parse_sets(&set)?;
            let text = eom_model::file::to_toml(&choice.build(&overrides)?);
            match output {
                None => text,
                Some(path) => {
                    stderr.push_str(&output::status_line(
                        &path,
                        output::write_output(&path, &text)?,
                    ));
                    String::new()
                }
            }
        }
        Command::Aero(a) => {
            let req = aero::AeroRequest {
                alpha_deg: a.alpha,
                reference: a
                    .reference
                    .as_deref()
                    .map(aero::parse_reference)
                    .transpose()?,
                density: a.rho,
                speed: a.speed,
            };
            let r = aero::aero(&a.file, &req)?;
            match a.format {
                Format::Text => r.to_text(),
                Format::Json => json(&r)?,
            }
        }
        Command::Symbolic(a) => {
            let choice = ModelChoice::resolve(&a.model)?;
            // Checked as numbers (names, finiteness), kept as text for exact substitution.
            choice.parse_sets(&a.set)?;
            let texts: Vec<(String, String)> = a
                .set
                .iter()
                .filter_map(|s| s.split_once('='))
                .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
                .collect();
            let req = symbolic::SymbolicRequest {
                stability: a.stability,
                solve_for: a.solve_for,
                transfer: a.transfer,
                max_states: a.max_states,
            };
            if let Some(name) = &req.solve_for {
                choice.param(name)?;
            }
            if let Some(n) = req
                .max_states
                .filter(|&n| n == 0 || n > eom_sym::closed::MAX_CLOSED_FORM_STATES)
            {
                return Err(CliError::BadArgument {
                    argument: format!("--max-states {n}"),
                    problem: format!(
                        "closed forms are derived for 1 to {} states",
                        eom_sym::closed::MAX_CLOSED_FORM_STATES
                    ),
                });
            }
            let r = symbolic::symbolic(&choice, &texts, &req)?;
            match a.format {
                SymbolicFormat::Text => r.to_text(),
                SymbolicFormat::Latex => r.to_latex(),
                SymbolicFormat::Json => json(&r)?,
            }
        }
    };
    Ok(Output { stdout, stderr })
}

/// `eom analyze`: the analysis, printed, and the plots asked for.
fn run_analyze(a: &AnalyzeArgs, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&a.model)?;
    let overrides = choice.parse_sets(&a.set)?;
    let range = a.freq_range.as_deref().map(parse_freq_range).transpose()?;
    if a.points == Some(0) {
        return Err(CliError::BadArgument {
            argument: "--points 0".into(),
            problem: "at least one frequency is needed".into(),
        });
    }
    if let Some(n) = a.points.filter(|&n| n > params::MAX_FREQ_POINTS) {
        return Err(CliError::BadArgument {
            argument: format!("--points {n}"),
            problem: format!(
                "more than the limit of {} frequencies (a Bode plot needs a few hundred per \
                 decade at most)",
                params::MAX_FREQ_POINTS
            ),
        });
    }
    let plots = analyze_plots(a)?;
    if let Some(path) = &a.matrices {
        matrices::format_of("--matrices", path)?;
    }
    let bode = a.plot.is_some();
    let freq = (a.freq || range.is_some() || a.points.is_some() || bode).then_some(FreqRequest {
        range,
        points: a.points,
    });
    let opts = AnalyzeOptions {
        method: a.method.into(),
        freq,
        sensitivity: a.sensitivity,
    };
    let lin = analyze::linearize(&choice, &overrides, opts.method)?;
    let r = analyze::analyze_linearized(&choice, &overrides, &opts, &lin)?;
    let reduced =
        match &a.reduce {
            None => None,
            Some(text) => {
                let order =
                    match text.as_str() {
                        "default" => None,
                        t => Some(t.trim().parse::<usize>().map_err(|_| {
                            CliError::BadArgument {
                    argument: format!("--reduce {}", params::abbreviate(t)),
                    problem: "expected a number of states (or nothing, for the default order)"
                        .into(),
                }
                        })?),
                    };
                let req = reduce::ReduceRequest {
                    method: reduce_method(a.reduce_method.unwrap_or(ReduceMethodArg::Balanced)),
                    order,
                    tol: None,
                    band: None,
                    linearization: opts.method,
                };
                Some(reduce::report_of(&choice, &overrides, &lin, &req)?.0)
            }
        };
    for (option, path) in plots {
        let plot = match option {
            "--plot" => plot::bode::bode_of(&r)?,
            "--plot-poles" => plot::poles::pole_map_of(&r)?,
            _ => analyze_picture(a, option, &choice, &overrides, &lin)?,
        };
        plot.write(option, path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &a.matrices {
        let written = matrices::write_matrices("--matrices", path, &r.matrices.named())?;
        stderr.push_str(&output::status_line(path, written));
    }
    Ok(match (a.format, reduced) {
        (Format::Text, None) => r.to_text(),
        (Format::Text, Some(red)) => format!("{}\n{}", r.to_text(), red.to_text()),
        (Format::Json, None) => json(&r)?,
        (Format::Json, Some(red)) => {
            let mut v = serde_json::to_value(&r)?;
            if let Some(map) = v.as_object_mut() {
                map.insert("reduction".into(), serde_json::to_value(&red)?);
            }
            json(&v)?
        }
    })
}

/// `eom reduce`: the reduction, printed, and its plot.
fn run_reduce(a: &ReduceArgs, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&a.model)?;
    let overrides = choice.parse_sets(&a.set)?;
    if let Some(path) = &a.plot {
        plot::check_target("--plot", path)?;
    }
    if let Some(path) = &a.matrices {
        matrices::format_of("--matrices", path)?;
    }
    let band = a
        .band
        .as_deref()
        .map(|b| {
            params::parse_band(b).map_err(|problem| CliError::BadArgument {
                argument: format!("--band {}", params::abbreviate(b)),
                problem,
            })
        })
        .transpose()?;
    let method = reduce_method(a.method);
    let req = reduce::ReduceRequest {
        method,
        order: a.order,
        tol: a.tol,
        band,
        linearization: a.linearize.into(),
    };
    let (r, _) = reduce::reduce(&choice, &overrides, &req)?;
    if let Some(path) = &a.plot {
        let plot = plot::hankel::hankel_plot(&r)?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &a.matrices {
        let written = matrices::write_matrices("--matrices", path, &r.matrices.named())?;
        stderr.push_str(&output::status_line(path, written));
    }
    Ok(match a.format {
        Format::Text => r.to_text(),
        Format::Json => json(&r)?,
    })
}

/// The reducer's method for a command-line choice.
fn reduce_method(m: ReduceMethodArg) -> eom_num::model_reduction::ReductionMethod {
    use eom_num::model_reduction::ReductionMethod;
    match m {
        ReduceMethodArg::Balanced => ReductionMethod::Balanced,
        ReduceMethodArg::Matchdc => ReductionMethod::MatchDc,
        ReduceMethodArg::Modal => ReductionMethod::Modal,
    }
}

/// The time-response and mode-shape pictures of `eom analyze`.
fn analyze_picture(
    a: &AnalyzeArgs,
    option: &str,
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    lin: &eom_model::Linearization,
) -> Result<plot::Plot, CliError> {
    let ss = &lin.state_space;
    let modes = pictures::modes_of(ss, lin.structural_zeros.len())?;
    let name = &choice.name;
    match option {
        "--plot-step" => pictures::step_impulse_plot(name, ss),
        "--plot-initial" => {
            let k = match a.mode {
                Some(k) => k,
                None => pictures::default_mode(&modes).ok_or_else(|| {
                    CliError::NothingToDraw(format!("the model `{name}` has no nonzero mode"))
                })?,
            };
            pictures::initial_plot(name, ss, &modes, k)
        }
        _ => {
            let model = choice.build(overrides)?.nominal()?;
            let which = match a.mode {
                Some(k) => vec![k],
                None => pictures::drawable_modes(&modes),
            };
            if which.is_empty() {
                return Err(CliError::NothingToDraw(format!(
                    "no mode of `{name}` moves a body: nothing to draw"
                )));
            }
            let parts = which
                .iter()
                .map(|k| pictures::mode_shape_svg(name, &model, ss, &modes, *k))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(plot::Plot {
                svg: pictures::stack_svgs(&parts),
                notes: Vec::new(),
            })
        }
    }
}

/// `eom sweep MODEL`: the sweep, printed, and its plots.
fn run_sweep(s: &SweepArgs, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&s.model)?;
    let spec = SweepSpec::parse(&s.param)?;
    choice.param(&spec.name)?;
    let overrides = choice.parse_sets(&s.set)?;
    let zoom = sweep_plot_options(s, &spec)?;
    let bar = progress::Progress::new(quiet, spec.count as u64, &format!("sweep {}", s.model));
    let r = sweep::sweep_with(&choice, &spec, &overrides, &|| bar.tick())?;
    bar.finish();
    let unit = choice.param(&spec.name)?.unit.clone();
    if let Some(path) = &s.plot {
        let plot = plot::sweep::sweep_plot(&r.model, &r.result, &unit, zoom)?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &s.plot_locus {
        let plot = plot::locus::locus_plot(&r.model, &r.result, &unit)?;
        plot.write("--plot-locus", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    Ok(match s.format {
        SweepFormat::Text => r.to_text(),
        SweepFormat::Json => json(&r)?,
        SweepFormat::Csv => {
            // Keep the CSV clean; the evaluation note goes to standard error.
            stderr.push_str(&r.evaluation_note());
            r.to_csv()
        }
    })
}

/// Checks the plot options of `eom sweep` before the sweep runs; returns the zoom.
fn sweep_plot_options(
    s: &SweepArgs,
    spec: &SweepSpec,
) -> Result<Option<plot::zoom::Zoom>, CliError> {
    if let Some(path) = &s.plot {
        check_sweep_plot(&s.param, spec, path)?;
    }
    if let Some(path) = &s.plot_locus {
        plot::check_target("--plot-locus", path)?;
        if let Some(p) = &s.plot {
            plot::check_distinct(("--plot", p), ("--plot-locus", path))?;
        }
    }
    let zoom = s.zoom.as_deref().map(plot::zoom::Zoom::parse).transpose()?;
    if zoom.is_some() && s.plot.is_none() {
        return Err(CliError::BadArgument {
            argument: "--zoom".into(),
            problem: "the zoom is a panel of the --plot FILE.svg: give --plot too".into(),
        });
    }
    Ok(zoom)
}

/// `eom sweep A --compare B`: both sweeps over the same grid, reported one after the other
/// (JSON: `{"sweeps": [A, B]}`), drawn in one plot with `--plot`.
fn sweep_compare(s: &SweepArgs, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    let other = s.compare.as_deref().unwrap_or_default();
    if s.format == SweepFormat::Csv {
        return Err(CliError::BadArgument {
            argument: format!("--compare {other}"),
            problem: "not with --format csv (one table per model): use text or json".into(),
        });
    }
    let spec = SweepSpec::parse(&s.param)?;
    let zoom = sweep_plot_options(s, &spec)?;
    if s.plot_locus.is_some() {
        return Err(CliError::BadArgument {
            argument: format!("--compare {other}"),
            problem: "not with --plot-locus (one locus per model): sweep each model".into(),
        });
    }
    let mut reports = Vec::new();
    for name in [s.model.as_str(), other] {
        let choice = ModelChoice::resolve(name)?;
        choice.param(&spec.name)?;
        let overrides = choice.parse_sets(&s.set)?;
        let bar = progress::Progress::new(quiet, spec.count as u64, &format!("sweep {name}"));
        reports.push((
            sweep::sweep_with(&choice, &spec, &overrides, &|| bar.tick())?,
            choice,
        ));
        bar.finish();
    }
    let (a, b) = (&reports[0], &reports[1]);
    if let Some(path) = &s.plot {
        let unit = a.1.param(&spec.name)?.unit.clone();
        let plot = plot::compare::compare_plot(
            (&a.0.model, &a.0.result),
            (&b.0.model, &b.0.result),
            &unit,
            zoom,
        )?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    Ok(match s.format {
        SweepFormat::Json => json(&serde_json::json!({ "sweeps": [&a.0, &b.0] }))?,
        _ => format!(
            "{}
{}",
            a.0.to_text(),
            b.0.to_text()
        ),
    })
}

/// The plot files asked of `eom analyze`, checked before the analysis runs.
fn analyze_plots(a: &AnalyzeArgs) -> Result<Vec<(&'static str, &Path)>, CliError> {
    let plots: Vec<(&'static str, &Path)> = [
        ("--plot", a.plot.as_deref()),
        ("--plot-poles", a.plot_poles.as_deref()),
        ("--plot-step", a.plot_step.as_deref()),
        ("--plot-initial", a.plot_initial.as_deref()),
        ("--plot-modes", a.plot_modes.as_deref()),
    ]
    .into_iter()
    .filter_map(|(o, p)| p.map(|p| (o, p)))
    .collect();
    for (option, path) in &plots {
        plot::check_target(option, path)?;
    }
    for (k, first) in plots.iter().enumerate() {
        for second in &plots[k + 1..] {
            plot::check_distinct(*first, *second)?;
        }
    }
    if a.mode.is_some() && a.plot_initial.is_none() && a.plot_modes.is_none() {
        return Err(CliError::BadArgument {
            argument: "--mode".into(),
            problem: "it chooses the mode of --plot-initial or --plot-modes: give one of them"
                .into(),
        });
    }
    Ok(plots)
}

/// Checks `eom sweep --plot` before the sweep runs: the file, and a parameter range of
/// nonzero width (a single value has no axis to draw the branches along).
fn check_sweep_plot(param: &str, spec: &SweepSpec, path: &Path) -> Result<(), CliError> {
    plot::check_target("--plot", path)?;
    let (lo, hi) = spec.bounds();
    if spec.count < 2 || lo == hi {
        return Err(CliError::BadArgument {
            argument: format!("--param {param}"),
            problem: "--plot needs a range of nonzero width: at least two values \
                      (COUNT ≥ 2) with START ≠ STOP"
                .into(),
        });
    }
    Ok(())
}

fn write_all(mut w: impl Write, text: &str, what: &str) -> Result<(), CliError> {
    match w.write_all(text.as_bytes()).and_then(|_| w.flush()) {
        // A closed pipe (`eom … | head`) is the reader's choice, not a failure.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => r.map_err(|source| CliError::Io {
            path: what.into(),
            source,
        }),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = params::memory_limit_from_env()
        .and_then(|_| run(cli))
        .and_then(|out| {
            // Messages and statuses may quote names and file text: never raw control
            // characters on a terminal. Standard output is left as it is unless it is a
            // terminal (it may be a file that must stay byte-exact, JSON for instance).
            let stderr = eom_text::for_terminal(&out.stderr);
            write_all(std::io::stderr().lock(), &stderr, "standard error")?;
            let stdout = std::io::stdout();
            if stdout.is_terminal() {
                write_all(
                    stdout.lock(),
                    &eom_text::for_terminal(&out.stdout),
                    "standard output",
                )
            } else {
                write_all(stdout.lock(), &out.stdout, "standard output")
            }
        });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Nothing more can be done if standard error is closed too.
            let message = e.to_string();
            let _ = writeln!(
                std::io::stderr(),
                "error: {}",
                eom_text::for_terminal(&message)
            );
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}
