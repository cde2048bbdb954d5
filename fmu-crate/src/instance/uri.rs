//! fmuResourceLocation: a file URI made a path of this platform (drive letters and UNC shares on Windows).

use std::path::PathBuf;

/// Turns a file URI (fmuResourceLocation) into a path of this platform: `file:///a/b%20c/` -> `/a/b c/`.
pub fn uri_to_path(uri: &str) -> Option<PathBuf> {
    uri_to_path_for(uri, cfg!(windows)).map(PathBuf::from)
}

/// [`uri_to_path`] for a given platform. On Windows a drive letter loses the URI's leading
/// slash (`file:///C:/x` -> `C:/x`, as fmpy and the Windows tools write it) and a host names a
/// network share (`file://server/share/x` -> `//server/share/x`, a UNC path); elsewhere only
/// an empty host or `localhost` is local.
fn uri_to_path_for(uri: &str, windows: bool) -> Option<String> {
    let rest = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))?;
    let b = rest.as_bytes();
    let drive = b.len() >= 2 && b[0].is_ascii_alphabetic() && (b[1] == b':' || b[1] == b'|');
    let rest = if let Some(r) = rest.strip_prefix("localhost/") {
        format!("/{r}")
    } else if windows && drive {
        // file://C:/x and file:C:/x (malformed, but written by some Windows tools; | is the
        // old form of the drive colon)
        format!("/{}:{}", &rest[..1], &rest[2..])
    } else if windows && !rest.starts_with('/') && uri.starts_with("file://") && !rest.is_empty() {
        format!("//{rest}")
    } else {
        rest.to_string()
    };
    if !rest.starts_with('/') {
        return None;
    }
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let path = String::from_utf8(out).ok()?;
    let b = path.as_bytes();
    if windows
        && b.len() >= 3
        && b[0] == b'/'
        && b[1].is_ascii_alphabetic()
        && (b[2] == b':' || b[2] == b'|')
    {
        return Some(format!("{}:{}", &path[1..2], &path[3..]));
    }
    Some(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uri_paths() {
        assert_eq!(
            uri_to_path("file:///tmp/a%20b/res/"),
            Some(PathBuf::from("/tmp/a b/res/"))
        );
        assert_eq!(uri_to_path("file:/tmp/x"), Some(PathBuf::from("/tmp/x")));
        assert_eq!(
            uri_to_path("file://localhost/tmp/x"),
            Some(PathBuf::from("/tmp/x"))
        );
        assert_eq!(uri_to_path("http://x/y"), None);
        assert_eq!(uri_to_path("file:///tmp/%zz"), None);
    }

    #[test]
    fn windows_file_uris_become_drive_and_unc_paths() {
        let w = |u| uri_to_path_for(u, true);
        assert_eq!(
            w("file:///C:/Users/a%20b/res/").as_deref(),
            Some("C:/Users/a b/res/")
        );
        assert_eq!(
            w("file:/D:/fmu/resources").as_deref(),
            Some("D:/fmu/resources")
        );
        assert_eq!(w("file://localhost/C:/x").as_deref(), Some("C:/x"));
        assert_eq!(
            w("file://server/share/res").as_deref(),
            Some("//server/share/res")
        );
        assert_eq!(w("file:///tmp/x").as_deref(), Some("/tmp/x"));
        assert_eq!(w("file://C:/x/res").as_deref(), Some("C:/x/res"));
        assert_eq!(w("file:///C|/x").as_deref(), Some("C:/x"));
        assert_eq!(w("file://D|/x").as_deref(), Some("D:/x"));
        // elsewhere a drive-letter-like segment is an ordinary folder and a host is not local
        let l = |u| uri_to_path_for(u, false);
        assert_eq!(l("file:///C:/x").as_deref(), Some("/C:/x"));
        assert_eq!(l("file://server/share/res"), None);
    }
}
