//! The phase portraits are figures a paper can use: title, legend, axis labels with units and
//! ticks in the SVG as text, the scatter as embedded PNG images, and the file under 1 MB
//! however many contacts it shows (the worst case for size: points spread uniformly, so that
//! every pixel of both panels is hit and the PNG compresses least).

use noslip_sim::boundary_map::Body;
use noslip_sim::portrait::{Axes, Portrait};
use rand::{Rng, SeedableRng};

/// `count` points spread over both panels' whole squares (seeded).
fn uniform(count: usize, seed: u64) -> Vec<[f64; 4]> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            [
                rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
                rng.random_range(-std::f64::consts::FRAC_PI_2..std::f64::consts::FRAC_PI_2),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ]
        })
        .collect()
}

fn portrait(points: Vec<[f64; 4]>, axes: Axes) -> Portrait {
    Portrait {
        body: Body::Obstacle(0),
        axes,
        count: points.len() as u64 + 7,
        points,
    }
}

/// The base64 payloads of the SVG's embedded images.
fn images(svg: &str) -> Vec<&str> {
    svg.split("href=\"data:image/png;base64,")
        .skip(1)
        .map(|s| &s[..s.find('"').expect("a closed attribute")])
        .collect()
}

#[test]
fn the_svg_has_labels_units_title_legend_and_two_embedded_scatters() {
    for two_d in [true, false] {
        for angular in [true, false] {
            let axes = Axes { two_d, angular };
            let p = portrait(uniform(1000, 1), axes);
            let svg = p.svg("demo.toml").unwrap();
            for label in axes.labels().concat() {
                // As the SVG escapes text (plotters-svg: `&`, `<`, `>`, quotes).
                let escaped = label.replace('&', "&amp;").replace('\'', "&apos;");
                assert!(svg.contains(&escaped), "axis label {label:?} missing");
                assert!(label.contains('['), "{label:?} has no unit");
            }
            assert!(svg.contains("demo.toml: boundary map of obstacle 0"));
            assert!(svg
                .contains("state after each of 1007 contacts with obstacle 0 (first 1000 drawn)"));
            // Ticks: the sine axis has labelled ticks at -1 (2D), 0 and 1.
            for tick in [">\n0\n<", ">\n1\n<"] {
                assert!(svg.contains(tick), "tick {tick:?} missing");
            }
            if two_d {
                assert!(svg.contains(">\n-1\n<"));
            }
            let images = images(&svg);
            assert_eq!(images.len(), 2, "one raster per panel");
            for b64 in images {
                assert!(b64.starts_with("iVBORw0KGgo"), "a PNG signature");
            }
            // No point is drawn as a vector element: the scatter is only in the images.
            assert!(!svg.contains("<circle") && svg.matches("<rect").count() < 10);
        }
    }
}

#[test]
fn portraits_stay_under_a_megabyte_at_any_contact_count() {
    const MB: usize = 1 << 20;
    let axes = Axes {
        two_d: true,
        angular: true,
    };
    let mut sizes = Vec::new();
    for count in [20_000, 200_000, 1_000_000] {
        let p = portrait(uniform(count, count as u64), axes);
        let (svg, png) = (p.svg("dense.toml").unwrap(), p.png("dense.toml"));
        assert!(
            svg.len() < MB,
            "{count} contacts: SVG of {} bytes",
            svg.len()
        );
        assert!(
            png.len() < MB,
            "{count} contacts: PNG of {} bytes",
            png.len()
        );
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
        eprintln!(
            "{count} contacts: SVG {} bytes, PNG {} bytes",
            svg.len(),
            png.len()
        );
        sizes.push(svg.len());
    }
    // Dense enough that every pixel is hit: more contacts no longer grow the file much (the
    // shade levels change, the pixel count does not).
    assert!(sizes[2] < 2 * sizes[0], "{sizes:?}");
}
