//! The hooks of one C-family language ([`Language`]): what differs between languages (scalar
//! types, the names of `fma` and `sqrt`, qualifiers, the file's prelude and epilogue, what
//! follows each function); everything else is written once for all of them.

use super::precision::Precision;
use super::unit::{BatchParam, Unit};

/// The hooks of one C-family language. The shared driver ([`source`]) writes the file:
/// [`Language::prelude`], then per precision [`Language::begin`], each unit's function and
/// [`Language::after_function`], [`Language::end`]; then [`Language::epilogue`].
///
/// [`source`]: super::file::source
pub trait Language {
    /// The language's name in comments: `C99`, `OpenCL C`.
    fn title(&self) -> &'static str;
    /// The file extension: `h`, `cl`.
    fn extension(&self) -> &'static str;
    /// The qualifiers before `void` of a kernel function: `static inline`.
    fn qualifiers(&self) -> &'static str;
    /// The correctly rounded fused multiply-add of precision `p`: `fma`, `fmaf`.
    fn fma(&self, p: Precision) -> &'static str;
    /// The correctly rounded square root of precision `p`: `sqrt`, `sqrtf`.
    fn sqrt(&self, p: Precision) -> &'static str;
    /// The absolute value of precision `p`: `fabs`, `fabsf`.
    fn fabs(&self, p: Precision) -> &'static str;
    /// The first line of every function body (a pragma or macro), or `""`.
    fn body_prologue(&self) -> &'static str;
    /// The file's start after the common header comment: include guard, includes, pragmas.
    fn prelude(&self, guard: &str) -> String;
    /// The file's end.
    fn epilogue(&self, guard: &str) -> String;
    /// Before the functions of precision `p` (an extension guard), or `""`.
    fn begin(&self, p: Precision) -> String;
    /// After the functions of precision `p`.
    fn end(&self, p: Precision) -> String;
    /// What follows each function (OpenCL: its batch kernel, [`Language::batch`]), or `""`.
    fn after_function(&self, unit: &Unit, p: Precision) -> String;
    /// The batch entry point `{function}_batch(count, arrays..)` of the scalar function
    /// `function` with parameters `params` (OpenCL: a `__kernel`, one record per work item), or
    /// `""`.
    fn batch(&self, function: &str, params: &[BatchParam]) -> String;
    /// Lines describing the language-specific rules, for the header comment.
    fn notes(&self) -> Vec<String>;
}
