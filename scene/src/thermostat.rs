//! The `[thermostat]` table: the white-noise thermostat of a driven granular gas
//! (docs/granular.md, "A driven steady state").

use crate::ctx::Ctx;
use crate::raw::RawThermostat;
use crate::SceneError;
use num_rational::BigRational;

/// The white-noise thermostat (Williams & MacKintosh; van Noije & Ernst) applied as kicks: at
/// every time `k dt` (`k = 1, 2, ...`) each ball's velocity gets an independent normal
/// increment of variance `xi^2 dt` per component, less the increments' mass-weighted mean
/// (so the total momentum is unchanged). Spins are not kicked.
#[derive(Clone, Debug, PartialEq)]
pub struct Thermostat {
    /// `xi` (`thermostat.strength`, `> 0`).
    pub strength: BigRational,
    /// `dt` (`thermostat.interval`, `> 0`).
    pub interval: BigRational,
    /// The seed of the kicks' random stream (`thermostat.seed`, default 0).
    pub seed: u64,
}

/// The validated `[thermostat]` table: `kind = "white-noise"`, `strength` and `interval`
/// positive.
pub(crate) fn thermostat(
    ctx: &Ctx<'_>,
    raw: &Option<RawThermostat>,
) -> Result<Option<Thermostat>, SceneError> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    if raw.kind != "white-noise" {
        return Err(ctx.err(
            "thermostat.kind",
            format!("must be \"white-noise\", got {:?}", raw.kind),
        ));
    }
    Ok(Some(Thermostat {
        strength: ctx.positive("thermostat.strength", &raw.strength)?,
        interval: ctx.positive("thermostat.interval", &raw.interval)?,
        seed: raw.seed,
    }))
}

#[cfg(test)]
mod tests {
    use crate::Scene;

    const GAS: &str = "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"periodic\", \"periodic\"]\n\
                       [[species]]\nmass = 1\nradius = \"0.5\"\ncount = 4\n";

    fn scene(thermostat: &str) -> Result<Scene, String> {
        Scene::from_toml(&format!("{GAS}[thermostat]\n{thermostat}"), "t.toml")
            .map_err(|e| e.to_string())
    }

    #[test]
    fn a_white_noise_thermostat_is_read_exactly() {
        let s = scene("kind = \"white-noise\"\nstrength = \"0.25\"\ninterval = \"1/8\"\nseed = 3")
            .unwrap();
        let t = s.thermostat.unwrap();
        assert_eq!(t.strength.to_string(), "1/4");
        assert_eq!(t.interval.to_string(), "1/8");
        assert_eq!(t.seed, 3);
        let none = Scene::from_toml(GAS, "t.toml").unwrap();
        assert!(none.thermostat.is_none());
    }

    #[test]
    fn bad_thermostats_are_refused_naming_the_field() {
        let cases = [
            (
                "kind = \"vibrating\"\nstrength = 1\ninterval = 1",
                "t.toml: thermostat.kind: must be \"white-noise\", got \"vibrating\"",
            ),
            (
                "kind = \"white-noise\"\nstrength = 0\ninterval = 1",
                "t.toml: thermostat.strength: must be positive, got 0",
            ),
            (
                "kind = \"white-noise\"\nstrength = 1\ninterval = \"-1/2\"",
                "t.toml: thermostat.interval: must be positive, got -1/2",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(scene(text).unwrap_err(), message, "{text}");
        }
        for (text, key) in [
            ("kind = \"white-noise\"\ninterval = 1", "strength"),
            ("kind = \"white-noise\"\nstrength = 1", "interval"),
            (
                "kind = \"white-noise\"\nstrength = 1\ninterval = 1\nrate = 2",
                "rate",
            ),
            // Not numbers: refused by the number reader at their place in the file.
            (
                "kind = \"white-noise\"\nstrength = \"nan\"\ninterval = 1",
                "line 11, column 12",
            ),
            (
                "kind = \"white-noise\"\nstrength = 1\ninterval = \"inf\"",
                "line 12, column 12",
            ),
        ] {
            let e = scene(text).unwrap_err();
            assert!(e.contains(key), "{text}: {e}");
        }
    }
}
