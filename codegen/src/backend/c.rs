//! The C99 and OpenCL C back ends: the hooks of [`Language`] for each.

use super::language::Language;
use super::precision::Precision;
use super::unit::{BatchParam, Param, Unit};
use std::fmt::Write;

/// C99, as a self-contained header of `static inline` functions, usable from C++ as is.
#[derive(Clone, Copy, Debug, Default)]
pub struct C;

impl Language for C {
    fn title(&self) -> &'static str {
        "C99"
    }

    fn extension(&self) -> &'static str {
        "h"
    }

    fn qualifiers(&self) -> &'static str {
        "static inline NOSLIP_NO_CONTRACT"
    }

    fn fma(&self, p: Precision) -> &'static str {
        match p {
            Precision::F64 => "fma",
            Precision::F32 => "fmaf",
        }
    }

    fn sqrt(&self, p: Precision) -> &'static str {
        match p {
            Precision::F64 => "sqrt",
            Precision::F32 => "sqrtf",
        }
    }

    fn fabs(&self, p: Precision) -> &'static str {
        match p {
            Precision::F64 => "fabs",
            Precision::F32 => "fabsf",
        }
    }

    fn body_prologue(&self) -> &'static str {
        "NOSLIP_FP_CONTRACT_OFF"
    }

    fn prelude(&self, guard: &str) -> String {
        format!(
            "#ifndef {guard}_H\n\
             #define {guard}_H\n\
             \n\
             #include <float.h>\n\
             #include <math.h>\n\
             \n\
             #if defined(__FAST_MATH__)\n\
             #error \"noslip kernels: -ffast-math reorders and contracts floating-point operations; compile without it\"\n\
             #endif\n\
             #if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0\n\
             #error \"noslip kernels need FLT_EVAL_METHOD == 0: each operation rounded to its type (SSE2 on x86, not x87)\"\n\
             #endif\n\
             \n\
             /* No contraction of a * b + c into an FMA. clang honours the standard pragma at the\n\
             \x20* start of each body (unless given -ffp-contract=fast). GCC ignores it, contracts by\n\
             \x20* default in GNU C modes and in C++, and its vectorisers form FMAs (vfmaddsub) even under\n\
             \x20* -ffp-contract=off (GCC 12, x86-64, -O3 -march=native; tests/scene_backends.rs): so\n\
             \x20* under GCC each function is compiled with contraction and vectorisation off (GCC then\n\
             \x20* inlines it only into callers compiled with the same three options). */\n\
             #ifndef NOSLIP_NO_CONTRACT\n\
             #if defined(__GNUC__) && !defined(__clang__)\n\
             #define NOSLIP_NO_CONTRACT __attribute__((optimize(\"fp-contract=off\", \"no-tree-slp-vectorize\", \"no-tree-loop-vectorize\")))\n\
             #else\n\
             #define NOSLIP_NO_CONTRACT\n\
             #endif\n\
             #endif\n\
             #ifndef NOSLIP_FP_CONTRACT_OFF\n\
             #if defined(__clang__)\n\
             #define NOSLIP_FP_CONTRACT_OFF _Pragma(\"STDC FP_CONTRACT OFF\")\n\
             #else\n\
             #define NOSLIP_FP_CONTRACT_OFF\n\
             #endif\n\
             #endif\n"
        )
    }

    fn epilogue(&self, guard: &str) -> String {
        format!("#endif /* {guard}_H */\n")
    }

    fn begin(&self, _: Precision) -> String {
        String::new()
    }

    fn end(&self, _: Precision) -> String {
        String::new()
    }

    fn after_function(&self, _: &Unit, _: Precision) -> String {
        String::new()
    }

    fn batch(&self, _: &str, _: &[BatchParam]) -> String {
        String::new()
    }

    fn notes(&self) -> Vec<String> {
        vec![
            "Compile without -ffast-math and (clang) -ffp-contract=fast; otherwise the header itself".into(),
            "keeps GCC and clang from contracting (NOSLIP_NO_CONTRACT, NOSLIP_FP_CONTRACT_OFF), in C and C++.".into(),
            "The FMA forms call fma/fmaf from <math.h> (link -lm where libm is separate).".into(),
        ]
    }
}

/// OpenCL C (1.2): the kernels as device functions, and for each a batch `__kernel`
/// `NAME_batch(count, arrays..)` over arrays of structures, one contact per work item.
#[derive(Clone, Copy, Debug, Default)]
pub struct OpenCl;

impl Language for OpenCl {
    fn title(&self) -> &'static str {
        "OpenCL C"
    }

    fn extension(&self) -> &'static str {
        "cl"
    }

    fn qualifiers(&self) -> &'static str {
        "static inline"
    }

    fn fma(&self, _: Precision) -> &'static str {
        "fma"
    }

    fn sqrt(&self, _: Precision) -> &'static str {
        "sqrt"
    }

    fn fabs(&self, _: Precision) -> &'static str {
        "fabs"
    }

    fn body_prologue(&self) -> &'static str {
        ""
    }

    fn prelude(&self, guard: &str) -> String {
        format!(
            "#ifndef {guard}_CL\n\
             #define {guard}_CL\n\
             \n\
             /* No contraction of a * b + c into an FMA (OpenCL C allows it by default). */\n\
             #pragma OPENCL FP_CONTRACT OFF\n"
        )
    }

    fn epilogue(&self, guard: &str) -> String {
        format!("#endif /* {guard}_CL */\n")
    }

    fn begin(&self, p: Precision) -> String {
        match p {
            Precision::F64 => {
                "#if defined(cl_khr_fp64)\n#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n".into()
            }
            Precision::F32 => String::new(),
        }
    }

    fn end(&self, p: Precision) -> String {
        match p {
            Precision::F64 => "\n#endif /* cl_khr_fp64 */\n".into(),
            Precision::F32 => String::new(),
        }
    }

    fn after_function(&self, unit: &Unit, p: Precision) -> String {
        let ty = p.c_type();
        let state = unit.program.dim * (unit.program.dim - 1) / 2 + unit.program.dim;
        let params: Vec<BatchParam> = unit
            .params
            .iter()
            .map(|param| match param {
                Param::Array(a, elems) => BatchParam::input(a, ty, Some(elems.len())),
                Param::Scalar(a) => BatchParam::input(a, ty, None),
                Param::Out(a, _) => BatchParam::output(a, ty, state),
            })
            .collect();
        self.batch(&unit.function_name(p), &params)
    }

    fn batch(&self, name: &str, params: &[BatchParam]) -> String {
        let decls: Vec<String> = std::iter::once("const uint count".to_string())
            .chain(params.iter().map(|b| {
                let constness = if b.out { "" } else { "const " };
                format!("__global {constness}{} *{}", b.ty, b.name)
            }))
            .collect();
        let mut k = format!(
            "\n// {name} on contact i = get_global_id(0) < count: each parameter an array of\n\
             // count records of the scalar kernel's parameter (arrays of structures).\n\
             __kernel void {name}_batch({})\n{{\n    const size_t i = get_global_id(0);\n    if (i >= count) return;\n",
            decls.join(", ")
        );
        let mut args = Vec::new();
        for b in params {
            let (a, ty) = (&b.name, b.ty);
            match (b.len, b.out) {
                (Some(len), false) => {
                    let _ = writeln!(k, "    {ty} {a}_i[{len}];");
                    for e in 0..len {
                        let _ = writeln!(k, "    {a}_i[{e}] = {a}[i * {len} + {e}];");
                    }
                    args.push(format!("{a}_i"));
                }
                (None, _) => args.push(format!("{a}[i]")),
                (Some(len), true) => {
                    let _ = writeln!(k, "    {ty} {a}_i[{len}];");
                    args.push(format!("{a}_i"));
                }
            }
        }
        let _ = writeln!(k, "    {name}({});", args.join(", "));
        for b in params {
            if let (Some(len), true) = (b.len, b.out) {
                let a = &b.name;
                for e in 0..len {
                    let _ = writeln!(k, "    {a}[i * {len} + {e}] = {a}_i[{e}];");
                }
            }
        }
        k.push_str("}\n");
        k
    }

    fn notes(&self) -> Vec<String> {
        vec![
            "Build with -cl-fp32-correctly-rounded-divide-sqrt (OpenCL allows float `/` an error of".into(),
            "2.5 ulp otherwise) on a device whose float config has CL_FP_DENORM (else float subnormals".into(),
            "may flush to zero); the double kernels need cl_khr_fp64 (double `/` is correctly rounded).".into(),
            "Batch kernels NAME_batch(count, arrays..): one contact per work item, arrays of structures;".into(),
            "the certified companions' too (their bounds also need -cl-fp32-correctly-rounded-divide-sqrt),".into(),
            "and the energy-conserving correction's (noslip_conserve_*_batch: outputs the corrected after).".into(),
        ]
    }
}
