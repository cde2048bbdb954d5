//! fmi2Get/Set{Real,Integer,Boolean,String}: value arrays by value reference (FMI 2.0 sec. 2.1.7).

use super::*;

macro_rules! getter {
    ($fname:ident, $t:ty, $method:ident, $conv:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn $fname(
            c: f::fmi2Component,
            vr: *const f::fmi2ValueReference,
            nvr: usize,
            value: *mut $t,
        ) -> S {
            const F: &str = stringify!($fname);
            // SAFETY: `c` as in `with`; fmi2Get{Real,Integer,Boolean} pass vr as an array of
            // nvr value references and value as a writable array of nvr elements (FMI 2.0 sec.
            // 2.1.7); `slice`/`slice_mut` check both for null.
            unsafe {
                with(c, F, |comp| {
                    let (Some(vrs), Some(out)) = (slice(vr, nvr), slice_mut(value, nvr)) else {
                        return null_arg(&mut comp.inst, F, "vr or value");
                    };
                    for (r, o) in vrs.iter().zip(out.iter_mut()) {
                        match comp.inst.$method(*r) {
                            Ok(x) => *o = $conv(x),
                            Err(s) => return s,
                        }
                    }
                    Status::Ok
                })
            }
        }
    };
}

macro_rules! setter {
    ($fname:ident, $t:ty, $conv:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn $fname(
            c: f::fmi2Component,
            vr: *const f::fmi2ValueReference,
            nvr: usize,
            value: *const $t,
        ) -> S {
            const F: &str = stringify!($fname);
            // SAFETY: `c` as in `with`; fmi2Set{Real,Integer,Boolean} pass vr and value as
            // arrays of nvr elements (FMI 2.0 sec. 2.1.7); `slice` checks both for null; the
            // values are copied before the call returns.
            unsafe {
                with(c, F, |comp| {
                    let (Some(vrs), Some(vals)) = (slice(vr, nvr), slice(value, nvr)) else {
                        return null_arg(&mut comp.inst, F, "vr or value");
                    };
                    let items: Vec<(u32, Value)> = vrs
                        .iter()
                        .zip(vals.iter())
                        .map(|(r, x)| (*r, $conv(*x)))
                        .collect();
                    comp.inst.set_values(F, &items)
                })
            }
        }
    };
}

getter!(fmi2GetReal, f::fmi2Real, get_real, |x: f64| x);
getter!(fmi2GetInteger, f::fmi2Integer, get_integer, |x: i32| x);
getter!(fmi2GetBoolean, f::fmi2Boolean, get_boolean, |x: bool| x
    as f::fmi2Boolean);
setter!(fmi2SetReal, f::fmi2Real, Value::Real);
setter!(fmi2SetInteger, f::fmi2Integer, Value::Integer);
setter!(fmi2SetBoolean, f::fmi2Boolean, |x: f::fmi2Boolean| {
    Value::Boolean(x != 0)
});

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: f::fmi2Component,
    vr: *const f::fmi2ValueReference,
    nvr: usize,
    value: *mut f::fmi2String,
) -> S {
    const F: &str = "fmi2GetString";
    // SAFETY: `c` as in `with`; vr and value are arrays of nvr elements, value writable (FMI
    // 2.0 sec. 2.1.7), null-checked by `slice`/`slice_mut`; the returned strings live in
    // `comp.strings` until the next call on this instance, as sec. 2.1.7 requires of
    // fmi2GetString.
    unsafe {
        with(c, F, |comp| {
            let (Some(vrs), Some(out)) = (slice(vr, nvr), slice_mut(value, nvr)) else {
                return null_arg(&mut comp.inst, F, "vr or value");
            };
            get_strings(comp, vrs, out)
        })
    }
}

/// Writes the strings of `vrs` to `out` (fmi2GetString, fmi3GetString): they live in
/// `comp.strings` until the next call on the instance.
pub(super) fn get_strings(comp: &mut Component, vrs: &[u32], out: &mut [*const c_char]) -> Status {
    comp.strings.clear();
    for r in vrs {
        match comp.inst.get_string(*r) {
            Ok(s) => comp
                .strings
                .push(CString::new(s.replace('\0', " ")).unwrap_or_default()),
            Err(s) => return s,
        }
    }
    for (o, s) in out.iter_mut().zip(comp.strings.iter()) {
        *o = s.as_ptr();
    }
    Status::Ok
}

/// The values of a set of strings (fmi2SetString, fmi3SetString), copied; a null or
/// non-UTF-8 string refuses the call.
///
/// # Safety
/// Each non-null pointer of `vals` is a NUL-terminated string.
pub(super) unsafe fn string_values(
    comp: &mut Component,
    func: &str,
    vrs: &[u32],
    vals: &[*const c_char],
) -> Result<Vec<(u32, Value)>, Status> {
    let mut items = Vec::with_capacity(vrs.len());
    for (r, p) in vrs.iter().zip(vals.iter()) {
        // SAFETY: the caller's promise; `cstr` checks null.
        let Some(s) = (unsafe { cstr(*p) }) else {
            return Err(comp.inst.error(format!(
                "{func}: value for value reference {r} is a null pointer or not UTF-8; no value of this call was applied"
            )));
        };
        items.push((*r, Value::String(s.to_string())));
    }
    Ok(items)
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: f::fmi2Component,
    vr: *const f::fmi2ValueReference,
    nvr: usize,
    value: *const f::fmi2String,
) -> S {
    const F: &str = "fmi2SetString";
    // SAFETY: `c` as in `with`; vr and value are arrays of nvr elements and each value a NUL-
    // terminated string (FMI 2.0 sec. 2.1.7), null-checked by `slice` and `cstr`; the strings
    // are copied before the call returns (the importer may free them after it).
    unsafe {
        with(c, F, |comp| {
            let (Some(vrs), Some(vals)) = (slice(vr, nvr), slice(value, nvr)) else {
                return null_arg(&mut comp.inst, F, "vr or value");
            };
            match string_values(comp, F, vrs, vals) {
                Ok(items) => comp.inst.set_values(F, &items),
                Err(s) => s,
            }
        })
    }
}
