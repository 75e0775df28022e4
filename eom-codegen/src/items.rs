//! The module's items besides the evaluation functions: sizes, names, the parameters as a
//! struct, the error type, the slow path's failure search and the `StateSpace` wrapper.

use crate::problem::Mat;
use crate::render::Ctx;
use crate::{CodegenError, EmitOptions, param_table, str_array, validity_doc};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

fn us(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// Every item of the module but the evaluation functions, in this order.
pub(crate) fn module_items(
    ctx: &Ctx,
    opts: &EmitOptions,
    work_len: usize,
) -> Result<TokenStream, CodegenError> {
    let mut ts = sizes(ctx, work_len);
    ts.extend(names(ctx)?);
    ts.extend(params_struct(ctx)?);
    ts.extend(errors(opts.discrete));
    if opts.functions.abcd {
        ts.extend(state_space());
    }
    Ok(ts)
}

/// The dimensions and the structural non-zeros of the matrices.
fn sizes(ctx: &Ctx, work_len: usize) -> TokenStream {
    let p = ctx.problem;
    let ty = &ctx.ty;
    let names = &p.names;
    let (nx, nu, ny, nq, np, nc) = (
        us(names.states.len()),
        us(names.inputs.len()),
        us(names.outputs.len()),
        us(p.mats[Mat::Phys.index()].rows),
        us(p.params.len()),
        us(p.checks.len()),
    );
    let wl = us(work_len);
    let mut ts = quote! {
        /// The floating-point type of this module.
        pub type Real = #ty;
        /// Number of states (rows and columns of A).
        pub const N_STATES: usize = #nx;
        /// Number of inputs (columns of B and D).
        pub const N_INPUTS: usize = #nu;
        /// Number of outputs (rows of C and D).
        pub const N_OUTPUTS: usize = #ny;
        /// Number of physical coordinates (rows of Phys: six per body).
        pub const N_COORDS: usize = #nq;
        /// Number of parameters.
        pub const N_PARAMS: usize = #np;
        /// Number of validity checks.
        pub const N_CHECKS: usize = #nc;
        /// Length of the work buffer every evaluation function takes (0 when no function is
        /// split into chunks).
        pub const WORK_LEN: usize = #wl;
    };
    for m in Mat::ALL {
        let spec = &p.mats[m.index()];
        let len = format_ident!("{}_LEN", m.lower().to_uppercase());
        let nzn = format_ident!("{}_NONZEROS", m.lower().to_uppercase());
        let l = us(spec.rows * spec.cols);
        let doc1 = format!(
            " Length of the column-major array of `{}` ({} × {}).",
            m.variant(),
            spec.rows,
            spec.cols
        );
        let doc2 = format!(
            " The structural non-zeros of `{}` as `(row, column)`, column-major: the only entries the evaluation functions write ({} of {}).",
            m.variant(),
            spec.entries.len(),
            spec.rows * spec.cols
        );
        let nz: Vec<TokenStream> = spec
            .entries
            .iter()
            .map(|&(i, j, _)| {
                let (i, j) = (us(i), us(j));
                quote!((#i, #j))
            })
            .collect();
        let nnz = us(nz.len());
        ts.extend(quote! {
            #[doc = #doc1]
            pub const #len: usize = #l;
            #[doc = #doc2]
            pub const #nzn: [(usize, usize); #nnz] = [#(#nz),*];
        });
    }
    ts
}

/// Names, units, nominal values, tolerances and the validity checks.
fn names(ctx: &Ctx) -> Result<TokenStream, CodegenError> {
    let p = ctx.problem;
    let num = ctx.num;
    let names = &p.names;
    let mut ts = TokenStream::new();
    let pnames: Vec<String> = p.params.iter().map(|q| q.name.clone()).collect();
    let punits: Vec<String> = p.params.iter().map(|q| q.unit.clone()).collect();
    let nominal: Vec<TokenStream> = p
        .params
        .iter()
        .map(|q| num.lit(q.nominal, &q.name))
        .collect::<Result<_, _>>()?;
    let (sn, inn, iu, on, ou, bn) = (
        str_array(&names.states),
        str_array(&names.inputs),
        str_array(&names.input_units),
        str_array(&names.outputs),
        str_array(&names.output_units),
        str_array(&names.bodies),
    );
    let nb = us(names.bodies.len());
    let nin_u = us(names.input_units.len());
    let nout_u = us(names.output_units.len());
    let (pnames, punits) = (str_array(&pnames), str_array(&punits));
    let checks: Vec<String> = p.checks.iter().map(|c| c.what.clone()).collect();
    let checks = str_array(&checks);
    let ptol = num.lit(eom_model::reduce::PIVOT_TOLERANCE, "tolerance")?;
    let rtol = num.lit(eom_model::reduce::RANK_TOLERANCE, "tolerance")?;
    ts.extend(quote! {
        /// Parameter names, in the order of the parameter array.
        pub const PARAM_NAMES: [&str; N_PARAMS] = #pnames;
        /// Parameter units (empty when dimensionless or unknown).
        pub const PARAM_UNITS: [&str; N_PARAMS] = #punits;
        /// Nominal parameter values (the point where the pivots were chosen).
        pub const NOMINAL: [Real; N_PARAMS] = [#(#nominal),*];
        /// State names.
        pub const STATE_NAMES: [&str; N_STATES] = #sn;
        /// Input names.
        pub const INPUT_NAMES: [&str; N_INPUTS] = #inn;
        /// Input units.
        pub const INPUT_UNITS: [&str; #nin_u] = #iu;
        /// Output names.
        pub const OUTPUT_NAMES: [&str; N_OUTPUTS] = #on;
        /// Output units.
        pub const OUTPUT_UNITS: [&str; #nout_u] = #ou;
        /// Bodies: rows `6k..6k+6` of Phys are body `k`'s `x, y, z, rx, ry, rz`.
        pub const BODY_NAMES: [&str; #nb] = #bn;
        /// Relative size below which a pivot counts as broken down.
        pub const PIVOT_TOLERANCE: Real = #ptol;
        /// Relative size above which an entry that decided a rank invalidates the decision.
        pub const RANK_TOLERANCE: Real = #rtol;
    });
    let mut cdoc = vec![
        " The validity checks, in the order they are tested (the index in [`Error::Validity`])."
            .to_string(),
        String::new(),
    ];
    cdoc.extend(validity_doc(p));
    let cdoc = cdoc.iter().map(|l| quote!(#[doc = #l]));
    ts.extend(quote! {
        #(#cdoc)*
        pub const CHECKS: [&str; N_CHECKS] = #checks;
    });

    Ok(ts)
}

/// The parameters as a struct.
fn params_struct(ctx: &Ctx) -> Result<TokenStream, CodegenError> {
    let p = ctx.problem;
    let num = ctx.num;
    // Parameters as a struct.
    let mut pdoc = vec![
        " The parameters by name (see [`Params::to_array`] for the array form the kernels take)."
            .to_string(),
        String::new(),
    ];
    pdoc.extend(param_table(p));
    let pdoc = pdoc.iter().map(|l| quote!(#[doc = #l]));
    let mut fields = Vec::new();
    let mut inits = Vec::new();
    let mut from = Vec::new();
    let mut to = Vec::new();
    for (k, q) in p.params.iter().enumerate() {
        let f: TokenStream = q
            .field
            .parse()
            .map_err(|e| CodegenError::Syntax(format!("field {}: {e}", q.field)))?;
        let unit = if q.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", q.unit)
        };
        let doc = format!(
            " `{}`{unit}: {} (nominal {:?}).",
            q.name, q.description, q.nominal
        );
        let v = num.lit(q.nominal, &q.name)?;
        let kk = us(k);
        fields.push(quote!(#[doc = #doc] pub #f: Real));
        inits.push(quote!(#f: #v));
        from.push(quote!(#f: p[#kk]));
        to.push(quote!(self.#f));
    }
    Ok(quote! {
        #(#pdoc)*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Params {
            #(#fields,)*
        }
        impl Params {
            /// The nominal values.
            pub const NOMINAL: Params = Params { #(#inits,)* };
            /// From the array form (order of [`PARAM_NAMES`]).
            pub const fn from_array(p: &[Real; N_PARAMS]) -> Params {
                Params { #(#from,)* }
            }
            /// The array form the evaluation functions take.
            pub const fn to_array(&self) -> [Real; N_PARAMS] {
                [#(#to),*]
            }
        }
        impl Default for Params {
            fn default() -> Self {
                Params::NOMINAL
            }
        }

    })
}

/// The matrices and the error type of the module, and the slow path's failure search; the
/// discrete matrices `Ad`, `Bd` and the error `SampleTime` only with `eval_discrete`
/// (`discrete`), so that a module without it has no variant it never returns.
fn errors(discrete: bool) -> TokenStream {
    let (discrete_matrices, sample_time, sample_time_none, sample_time_text) = if discrete {
        (
            quote! {
                /// The discrete state matrix of `eval_discrete`.
                Ad,
                /// The discrete input matrix of `eval_discrete`.
                Bd,
            },
            quote! {
                /// The sample time given to `eval_discrete` is not finite and non-negative.
                SampleTime,
            },
            quote!(| Error::SampleTime),
            quote! {
                Error::SampleTime => write!(f, "the sample time is not finite and non-negative"),
            },
        )
    } else {
        Default::default()
    };
    let mut ts = quote! {
        /// The matrices, for error reports.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u8)]
        pub enum Matrix {
            /// State matrix (`N_STATES × N_STATES`).
            A,
            /// Input matrix (`N_STATES × N_INPUTS`).
            B,
            /// Output matrix (`N_OUTPUTS × N_STATES`).
            C,
            /// Feedthrough matrix (`N_OUTPUTS × N_INPUTS`).
            D,
            /// Map from the state to the physical coordinates (`N_COORDS × N_STATES`).
            Phys,
            #discrete_matrices
        }

        /// Why an evaluation produced no result.
        ///
        /// Eight bytes (a `u32` check index, `u16` row and column), so that on 64-bit targets
        /// `Result<(), Error>` is returned in a register. The Rust ABI returns a larger one
        /// (anything beyond a pointer's size that is not a pair of scalars) through a hidden
        /// pointer, and the fast path of a small evaluation function then moves every argument
        /// to the next register to call its slow path.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Error {
            /// The parameters are outside the validity region: this check fails.
            Validity {
                /// Index into [`CHECKS`] (its description: [`Error::what`]).
                check: u32,
            },
            /// An entry is a NaN or an infinity.
            NonFinite {
                /// The matrix.
                matrix: Matrix,
                /// Row of the entry.
                row: u16,
                /// Column of the entry.
                col: u16,
            },
            #sample_time
        }

        // `Result<(), Error>` fits in one register on 64-bit targets (returned in it).
        const _: () = if core::mem::size_of::<Result<(), Error>>() > 8 {
            panic!("Result<(), Error> must fit in 8 bytes, to be returned in a register");
        };

        impl Error {
            /// The description of the failing check (`CHECKS[check]`) for
            /// [`Error::Validity`]; `None` for [`Error::NonFinite`] (and for a check index
            /// out of range, which the evaluation functions never return).
            pub fn what(&self) -> Option<&'static str> {
                match *self {
                    Error::Validity { check } => CHECKS.get(check as usize).copied(),
                    Error::NonFinite { .. } #sample_time_none => None,
                }
            }
        }

        impl core::fmt::Display for Error {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                match self {
                    Error::Validity { check } => write!(f, "outside the validity region: check {} fails ({})", check, self.what().unwrap_or("unknown check")),
                    Error::NonFinite { matrix, row, col } => write!(f, "entry ({}, {}) of {:?} is not finite", row, col, matrix),
                    #sample_time_text
                }
            }
        }
    };
    ts.extend(quote! {
        /// The first failure in the order the interpreter reports them (slow path): a check
        /// that fails or whose pivot is not finite, else an entry that is not finite (the fast
        /// path tests finiteness with one sum, which may also overflow by itself: then `None`).
        #[inline(always)]
        fn failure(ok: &[bool], mag: &[Real], values: &[Real], entries: &[(Matrix, u16, u16, usize)]) -> Option<Error> {
            let mut check = 0;
            while check < ok.len() {
                if !ok[check] || !mag[check].is_finite() {
                    // `N_CHECKS ≤ u32::MAX`: the generator refuses larger models.
                    return Some(Error::Validity { check: check as u32 });
                }
                check += 1;
            }
            let mut k = 0;
            while k < entries.len() {
                let e = entries[k];
                if !values[e.3].is_finite() {
                    return Some(Error::NonFinite { matrix: e.0, row: e.1, col: e.2 });
                }
                k += 1;
            }
            None
        }
    });
    ts
}

/// `StateSpace`: A, B, C, D with the work buffer.
fn state_space() -> TokenStream {
    quote! {
        /// A, B, C, D with the work buffer, evaluated together by [`StateSpace::evaluate`]
        /// (no allocation; create it once, evaluate it often).
        #[derive(Clone, Debug, PartialEq)]
        pub struct StateSpace {
            a: [Real; A_LEN],
            b: [Real; B_LEN],
            c: [Real; C_LEN],
            d: [Real; D_LEN],
            work: [Real; WORK_LEN],
        }
        impl StateSpace {
            /// The constant entries set (see [`write_abcd_constants`]), all others zero.
            pub const fn new() -> Self {
                let mut s = StateSpace { a: [0.0; A_LEN], b: [0.0; B_LEN], c: [0.0; C_LEN], d: [0.0; D_LEN], work: [0.0; WORK_LEN] };
                write_abcd_constants(&mut s.a, &mut s.b, &mut s.c, &mut s.d);
                s
            }
            /// Evaluate at `params`, writing only the entries that depend on them
            /// ([`eval_abcd_varying`]). On error the matrices keep their previous values.
            pub fn evaluate(&mut self, params: &Params) -> Result<(), Error> {
                eval_abcd_varying(&params.to_array(), &mut self.a, &mut self.b, &mut self.c, &mut self.d, &mut self.work)
            }
            /// A, column-major (`a[i + j * N_STATES]`).
            pub fn a(&self) -> &[Real; A_LEN] { &self.a }
            /// B, column-major (`b[i + j * N_STATES]`).
            pub fn b(&self) -> &[Real; B_LEN] { &self.b }
            /// C, column-major (`c[i + j * N_OUTPUTS]`).
            pub fn c(&self) -> &[Real; C_LEN] { &self.c }
            /// D, column-major (`d[i + j * N_OUTPUTS]`).
            pub fn d(&self) -> &[Real; D_LEN] { &self.d }
        }
        impl Default for StateSpace {
            fn default() -> Self {
                Self::new()
            }
        }
    }
}
