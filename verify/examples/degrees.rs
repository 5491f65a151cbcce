fn main() {
    use noslip_codegen::model::Variant;
    use noslip_verify::checks::identity::{degree, Identity};
    for n in 2..=6 {
        for v in Variant::ALL {
            for &i in Identity::for_variant(v) {
                println!("{n} {v:?} {:?}: {}", i, degree(n, v, i));
            }
        }
    }
}
