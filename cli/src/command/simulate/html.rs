//! `noslip simulate --html FILE`: the run as an animation in one self-contained HTML page
//! (`noslip_sim::animation`), a member of the output set like `--log`.

use super::paths::{lexical, not_a_file, same_dir, same_file, SET_FILES};
use super::Args;
use crate::exit::Failure;
use crate::publish::Staging;
use std::path::Path;

/// The set's file that a `--html` outside `--out` links to.
pub(super) const MEMBER: &str = "animation.html";

/// The member of the set that `--html` becomes: its own name when it is directly in `out`,
/// else [`MEMBER`] (the file outside becomes a link to it). Refused (exit 2), naming
/// `--html`: a file deeper inside `out`, a name of the set's own files or of `--log`'s or
/// `--boundary-map`'s member, the scene file, or the file of `--log` or `--boundary-map`.
pub(super) fn member(
    args: &Args,
    html: &Path,
    out: &Path,
    taken: &[Option<String>; 2],
) -> Result<String, Failure> {
    let refuse = |why: String| {
        Err(Failure::bad_input(format!(
            "--html: {}: {why}",
            html.display()
        )))
    };
    if same_file(html, &args.file) {
        return refuse("is the scene file; the run would write over it".into());
    }
    for (option, other) in [("--log", &args.log), ("--boundary-map", &args.boundary_map)] {
        if other.as_deref().is_some_and(|o| same_file(o, html)) {
            return refuse(format!("is also {option}; the two need two files"));
        }
    }
    if let Some(why) = not_a_file(html, out, MEMBER) {
        return Err(Failure::bad_input(format!("--html: {why}")));
    }
    let name = html.file_name().map(|n| n.to_string_lossy().into_owned());
    let member = match name {
        Some(name) if same_dir(html.parent(), out) => name,
        _ if lexical(html).starts_with(lexical(out)) => {
            return refuse(format!(
                "is inside --out {} but not directly in it: the output set is replaced as a \
                 whole; put it in {} itself or outside",
                out.display(),
                out.display()
            ))
        }
        _ => MEMBER.to_string(),
    };
    if SET_FILES.contains(&member.as_str()) || member.starts_with("portrait-") {
        return refuse(format!(
            "would replace the set's own file {member} in {}",
            out.display()
        ));
    }
    if taken.iter().flatten().any(|t| *t == member) {
        return refuse(format!(
            "would be the set's file {member}, as --log or --boundary-map is; name them differently"
        ));
    }
    Ok(member)
}

/// Stage the page as `member` of the set (and `html` as a link to it when outside `--out`;
/// a stream such as `/dev/stdout` is written directly). `Err`: the set cannot be staged
/// (nothing is published); `Ok(Some(failure))`: the stream could not take the page, which
/// fails the command (exit 1) after the rest of the set is published and the summary
/// printed, as a failed `--log` does.
pub(super) fn publish(
    set: &mut Staging,
    html: &Path,
    member: &str,
    page: &str,
) -> Result<Option<Failure>, Failure> {
    let direct = same_dir(html.parent(), set.target());
    let at = if direct {
        set.path(member)
    } else {
        set.side(html, member)
            .map_err(|e| crate::exit::publish_failure(&e))?
    };
    if at == set.path(member) {
        set.write(member, page.as_bytes())
            .map_err(|e| crate::exit::publish_failure(&e))?;
        return Ok(None);
    }
    Ok(std::fs::write(&at, page).err().map(|e| {
        Failure::output(format!(
            "cannot write the animation {}: {e} (the summary was written)",
            html.display()
        ))
    }))
}
