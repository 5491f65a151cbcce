//! The verifier can fail: deliberately corrupted kernels (a flipped sign, a dropped term, a
//! wrong constant, injected into the generator's DAG) are each caught, and the report says
//! by which checks. The uncorrupted DAG evaluation passes every check (the control).

use noslip_codegen::model::Variant;
use noslip_verify::suite::{identity_checks, Options};
use noslip_verify::under_test::{mutated, Mutation};

const OPTS: Options = Options {
    points: 2,
    configurations: 1,
    seed: 11,
};

#[test]
fn every_mutation_is_caught_by_some_check() {
    for variant in Variant::ALL {
        for mutation in Mutation::ALL {
            let kernel = mutated::<3, 3>(variant, Some(mutation));
            let results = identity_checks::<3, 3>(kernel.as_ref(), variant, &OPTS, &mut |_| {});
            let caught: Vec<&str> = results
                .iter()
                .filter(|r| !r.passed)
                .map(|r| r.check.as_str())
                .collect();
            println!("{variant:?}, {}: caught by {caught:?}", mutation.name());
            assert!(
                !caught.is_empty(),
                "{variant:?}: {} slipped through",
                mutation.name()
            );
            assert!(
                caught.iter().any(|c| c.starts_with("map: reflection")),
                "{variant:?}: the reflection check must catch {}",
                mutation.name()
            );
        }
    }
}

/// The control: the same evaluation of the same DAG as the mutations' (`n = 3`), with no
/// mutation, passes every check (and at `n = 2` too).
#[test]
fn the_uncorrupted_dag_passes_every_check() {
    for variant in Variant::ALL {
        let kernel = mutated::<3, 3>(variant, None);
        let results = identity_checks::<3, 3>(kernel.as_ref(), variant, &OPTS, &mut |_| {});
        assert!(results.iter().all(|r| r.passed), "n = 3: {results:?}");
        let kernel = mutated::<2, 1>(variant, None);
        let results = identity_checks::<2, 1>(kernel.as_ref(), variant, &OPTS, &mut |_| {});
        assert!(results.iter().all(|r| r.passed), "n = 2: {results:?}");
    }
}
