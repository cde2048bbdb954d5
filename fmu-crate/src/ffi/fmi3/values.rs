//! fmi3Get/Set of every type: Float64, Int32, Boolean and String of the variable table, the field arrays (Float64, Int32), `time` and the structural parameter `n_field` (UInt64); the types without variables refuse every value reference (FMI 3.0 sec. 2.3.2).

use super::*;
use crate::arrays::{array_of, Field, Sampled, VR_N_FIELD, VR_TIME};
use crate::model_description3::type_name;
use crate::vars::Kind;

/// The FMI 3.0 type name of a value reference's variable (None: unknown).
fn type_of(comp: &Component, vr: u32) -> Option<&'static str> {
    match vr {
        VR_TIME => Some("Float64"),
        VR_N_FIELD => Some("UInt64"),
        _ => array_of(vr).map(|a| type_name(a.kind)).or_else(|| {
            comp.inst
                .table()
                .iter()
                .find(|v| v.vr == vr)
                .map(|v| type_name(v.kind))
        }),
    }
}

/// Refuses the value reference `vr` for a call of type `want`.
fn wrong_type(comp: &mut Component, func: &str, vr: u32, want: &str) -> Status {
    match type_of(comp, vr) {
        Some(t) => comp.inst.error(format!(
            "{func}: value reference {vr} is of type {t}, not {want}"
        )),
        None => comp
            .inst
            .error(format!("{func}: unknown value reference {vr}")),
    }
}

/// Checks that `n` values are given for `vrs` (each array n_field of them, each scalar one).
fn check_count(
    comp: &mut Component,
    part: &Part,
    func: &str,
    vrs: &[u32],
    n: usize,
) -> Result<(), Status> {
    let want: usize = vrs
        .iter()
        .map(|vr| {
            if array_of(*vr).is_some() {
                part.n_field as usize
            } else {
                1
            }
        })
        .sum();
    if want == n {
        Ok(())
    } else {
        Err(comp.inst.error(format!(
            "{func}: nValues = {n}, but the {} value references hold {want} values (each field array n_field = {})",
            vrs.len(),
            part.n_field
        )))
    }
}

/// Gets values of one type: scalars by `scalar`, arrays by `array` from the field (sampled
/// once per call, and only if an array is read).
fn get_values<T: Copy>(
    comp: &mut Component,
    part: &Part,
    func: &str,
    (vrs, out): (&[u32], &mut [T]),
    kind: Kind,
    scalar: impl Fn(&mut Instance, u32) -> Result<T, Status>,
    array: impl Fn(&Sampled, Field) -> Vec<T>,
) -> Status {
    if let Err(s) = check_count(comp, part, func, vrs, out.len()) {
        return s;
    }
    let mut field: Option<Sampled> = None;
    let mut k = 0;
    for &vr in vrs {
        match array_of(vr) {
            Some(a) if a.kind == kind => {
                if field.is_none() {
                    match comp.inst.field(func) {
                        Ok((pts, semi)) => {
                            field =
                                Some(arrays::sample(pts.as_deref(), semi, part.n_field as usize))
                        }
                        Err(s) => return s,
                    }
                }
                if let Some(f) = &field {
                    let v = array(f, a.field);
                    out[k..k + v.len()].copy_from_slice(&v);
                    k += v.len();
                }
            }
            Some(_) => return wrong_type(comp, func, vr, type_name(kind)),
            None => match scalar(&mut comp.inst, vr) {
                Ok(x) => {
                    out[k] = x;
                    k += 1;
                }
                Err(s) => return s,
            },
        }
    }
    Status::Ok
}

/// Sets scalars of the variable table (refused in configuration mode, and for the arrays).
fn set_values(
    comp: &mut Component,
    part: &Part,
    func: &str,
    vrs: &[u32],
    vals: Vec<Value>,
) -> Status {
    if let Err(s) = not_configuring(comp, part, func) {
        return s;
    }
    if vrs.len() != vals.len() {
        return comp.inst.error(format!(
            "{func}: nValues = {}, but {} value references of scalars are given",
            vals.len(),
            vrs.len()
        ));
    }
    if let Some(vr) = vrs
        .iter()
        .find(|vr| array_of(**vr).is_some() || **vr == VR_TIME)
    {
        let name = array_of(*vr).map_or("time", |a| a.name);
        return comp.inst.error(format!(
            "{func}: cannot set {name} (value reference {vr}): it is an output"
        ));
    }
    let items: Vec<(u32, Value)> = vrs.iter().copied().zip(vals).collect();
    comp.inst.set_values(func, &items)
}

macro_rules! getter3 {
    ($fname:ident, $t:ty, $kind:expr, $scalar:expr, $array:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn $fname(
            instance: f3::fmi3Instance,
            valueReferences: *const f3::fmi3ValueReference,
            nValueReferences: usize,
            values: *mut $t,
            nValues: usize,
        ) -> St {
            const F: &str = stringify!($fname);
            // SAFETY: `instance` as in `with3`; valueReferences is an array of
            // nValueReferences and values a writable array of nValues elements (FMI 3.0 sec.
            // 2.3.2); `slice`/`slice_mut` check both for null.
            unsafe {
                with3(instance, F, |comp, part| {
                    let (Some(vrs), Some(out)) = (
                        slice(valueReferences, nValueReferences),
                        slice_mut(values, nValues),
                    ) else {
                        return null_arg(&mut comp.inst, F, "valueReferences or values");
                    };
                    get_values(comp, part, F, (vrs, out), $kind, $scalar, $array)
                })
            }
        }
    };
}

macro_rules! setter3 {
    ($fname:ident, $t:ty, $read:ty, $conv:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn $fname(
            instance: f3::fmi3Instance,
            valueReferences: *const f3::fmi3ValueReference,
            nValueReferences: usize,
            values: *const $t,
            nValues: usize,
        ) -> St {
            const F: &str = stringify!($fname);
            // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
            // nValueReferences and nValues elements (FMI 3.0 sec. 2.3.2); `slice` checks both
            // for null; the values are copied before the call returns.
            unsafe {
                with3(instance, F, |comp, part| {
                    let (Some(vrs), Some(vals)) = (
                        slice(valueReferences, nValueReferences),
                        slice(values as *const $read, nValues),
                    ) else {
                        return null_arg(&mut comp.inst, F, "valueReferences or values");
                    };
                    let vals: Vec<Value> = vals.iter().map($conv).collect();
                    set_values(comp, part, F, vrs, vals)
                })
            }
        }
    };
}

getter3!(
    fmi3GetFloat64,
    f3::fmi3Float64,
    Kind::Real,
    |i: &mut Instance, vr| if vr == VR_TIME {
        Ok(i.time())
    } else {
        i.get_real(vr)
    },
    |s: &Sampled, f| s.real(f).map(<[f64]>::to_vec).unwrap_or_default()
);
getter3!(
    fmi3GetInt32,
    f3::fmi3Int32,
    Kind::Integer,
    |i: &mut Instance, vr| i.get_integer(vr),
    |s: &Sampled, _| s.regime.clone()
);
setter3!(fmi3SetFloat64, f3::fmi3Float64, f64, |x: &f64| Value::Real(
    *x
));
setter3!(fmi3SetInt32, f3::fmi3Int32, i32, |x: &i32| Value::Integer(
    *x
));
// fmi3Boolean values are read as bytes (any non-zero byte is true: no invalid bool is formed)
setter3!(
    fmi3SetBoolean,
    f3::fmi3Boolean,
    u8,
    |x: &u8| Value::Boolean(*x != 0)
);

#[no_mangle]
pub unsafe extern "C" fn fmi3GetBoolean(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    values: *mut f3::fmi3Boolean,
    nValues: usize,
) -> St {
    const F: &str = "fmi3GetBoolean";
    // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
    // nValueReferences and nValues elements, values writable (FMI 3.0 sec. 2.3.2), null-checked.
    unsafe {
        with3(instance, F, |comp, part| {
            let (Some(vrs), Some(out)) = (
                slice(valueReferences, nValueReferences),
                slice_mut(values, nValues),
            ) else {
                return null_arg(&mut comp.inst, F, "valueReferences or values");
            };
            get_values(
                comp,
                part,
                F,
                (vrs, out),
                Kind::Boolean,
                |i, vr| i.get_boolean(vr),
                |_, _| Vec::new(),
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetString(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    values: *mut f3::fmi3String,
    nValues: usize,
) -> St {
    const F: &str = "fmi3GetString";
    // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
    // nValueReferences and nValues elements, values writable (FMI 3.0 sec. 2.3.2),
    // null-checked; the strings live in `comp.strings` until the next call on the instance.
    unsafe {
        with3(instance, F, |comp, part| {
            let (Some(vrs), Some(out)) = (
                slice(valueReferences, nValueReferences),
                slice_mut(values, nValues),
            ) else {
                return null_arg(&mut comp.inst, F, "valueReferences or values");
            };
            if let Err(s) = check_count(comp, part, F, vrs, out.len()) {
                return s;
            }
            super::super::values::get_strings(comp, vrs, out)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetString(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    values: *const f3::fmi3String,
    nValues: usize,
) -> St {
    const F: &str = "fmi3SetString";
    // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
    // nValueReferences and nValues elements, each value a NUL-terminated string (FMI 3.0 sec.
    // 2.3.2), null-checked by `slice` and `cstr`; the strings are copied.
    unsafe {
        with3(instance, F, |comp, part| {
            let (Some(vrs), Some(vals)) = (
                slice(valueReferences, nValueReferences),
                slice(values, nValues),
            ) else {
                return null_arg(&mut comp.inst, F, "valueReferences or values");
            };
            if vrs.len() != vals.len() {
                return comp.inst.error(format!(
                    "{F}: nValues = {} for {} value references of scalars",
                    vals.len(),
                    vrs.len()
                ));
            }
            match super::super::values::string_values(comp, F, vrs, vals) {
                Ok(items) => {
                    set_values(comp, part, F, vrs, items.into_iter().map(|i| i.1).collect())
                }
                Err(s) => s,
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt64(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    values: *mut f3::fmi3UInt64,
    nValues: usize,
) -> St {
    const F: &str = "fmi3GetUInt64";
    // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
    // nValueReferences and nValues elements, values writable (FMI 3.0 sec. 2.3.2), null-checked.
    unsafe {
        with3(instance, F, |comp, part| {
            let (Some(vrs), Some(out)) = (
                slice(valueReferences, nValueReferences),
                slice_mut(values, nValues),
            ) else {
                return null_arg(&mut comp.inst, F, "valueReferences or values");
            };
            if vrs.len() != out.len() {
                return comp.inst.error(format!(
                    "{F}: nValues = {} for {} value references of scalars",
                    out.len(),
                    vrs.len()
                ));
            }
            for (vr, o) in vrs.iter().zip(out.iter_mut()) {
                if *vr != VR_N_FIELD {
                    return wrong_type(comp, F, *vr, "UInt64");
                }
                *o = part.n_field;
            }
            Status::Ok
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt64(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    values: *const f3::fmi3UInt64,
    nValues: usize,
) -> St {
    const F: &str = "fmi3SetUInt64";
    // SAFETY: `instance` as in `with3`; valueReferences and values are arrays of
    // nValueReferences and nValues elements (FMI 3.0 sec. 2.3.2), null-checked; copied.
    unsafe {
        with3(instance, F, |comp, part| {
            let (Some(vrs), Some(vals)) = (
                slice(valueReferences, nValueReferences),
                slice(values, nValues),
            ) else {
                return null_arg(&mut comp.inst, F, "valueReferences or values");
            };
            if vrs.len() != vals.len() {
                return comp.inst.error(format!(
                    "{F}: nValues = {} for {} value references of scalars",
                    vals.len(),
                    vrs.len()
                ));
            }
            for (vr, x) in vrs.iter().zip(vals) {
                if *vr != VR_N_FIELD {
                    return wrong_type(comp, F, *vr, "UInt64");
                }
                if comp.inst.phase() != Phase::Instantiated {
                    return comp.inst.error(format!("{F}: cannot set n_field in state {}: it is a structural parameter (set it in Instantiated or ConfigurationMode)", comp.inst.phase().name()));
                }
                match check_n_field(*x) {
                    Ok(_) => part.n_field = *x,
                    Err(e) => return comp.inst.error(format!("{F}: {e} (value unchanged)")),
                }
            }
            Status::Ok
        })
    }
}

/// Exports get and set of a type without variables: every value reference is refused
/// (none is of that type); an empty call is fine.
macro_rules! no_variables {
    ($($get:ident, $set:ident, $t:ty, $name:literal;)*) => {
        $(
            #[no_mangle]
            pub unsafe extern "C" fn $get(
                instance: f3::fmi3Instance,
                valueReferences: *const f3::fmi3ValueReference,
                nValueReferences: usize,
                _values: *mut $t,
                _nValues: usize,
            ) -> St {
                // SAFETY: as `none_of_type`.
                unsafe { none_of_type(instance, stringify!($get), valueReferences, nValueReferences, $name) }
            }

            #[no_mangle]
            pub unsafe extern "C" fn $set(
                instance: f3::fmi3Instance,
                valueReferences: *const f3::fmi3ValueReference,
                nValueReferences: usize,
                _values: *const $t,
                _nValues: usize,
            ) -> St {
                // SAFETY: as `none_of_type`.
                unsafe { none_of_type(instance, stringify!($set), valueReferences, nValueReferences, $name) }
            }
        )*
    };
}

/// The body of a get or set of a type without variables.
unsafe fn none_of_type(
    instance: f3::fmi3Instance,
    func: &'static str,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    type_name: &'static str,
) -> St {
    // SAFETY: `instance` as in `with3`; valueReferences is an array of nValueReferences
    // elements (FMI 3.0 sec. 2.3.2), null-checked by `slice`; no value is read or written.
    unsafe {
        with3(instance, func, |comp, _| {
            match slice(valueReferences, nValueReferences) {
                None => null_arg(&mut comp.inst, func, "valueReferences"),
                Some([]) => Status::Ok,
                Some([vr, ..]) => wrong_type(comp, func, *vr, type_name),
            }
        })
    }
}

no_variables! {
    fmi3GetFloat32, fmi3SetFloat32, f3::fmi3Float32, "Float32";
    fmi3GetInt8, fmi3SetInt8, f3::fmi3Int8, "Int8";
    fmi3GetUInt8, fmi3SetUInt8, f3::fmi3UInt8, "UInt8";
    fmi3GetInt16, fmi3SetInt16, f3::fmi3Int16, "Int16";
    fmi3GetUInt16, fmi3SetUInt16, f3::fmi3UInt16, "UInt16";
    fmi3GetUInt32, fmi3SetUInt32, f3::fmi3UInt32, "UInt32";
    fmi3GetInt64, fmi3SetInt64, f3::fmi3Int64, "Int64";
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    _valueSizes: *mut usize,
    _values: *mut f3::fmi3Binary,
    _nValues: usize,
) -> St {
    // SAFETY: as `none_of_type`.
    unsafe {
        none_of_type(
            instance,
            "fmi3GetBinary",
            valueReferences,
            nValueReferences,
            "Binary",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    _valueSizes: *const usize,
    _values: *const f3::fmi3Binary,
    _nValues: usize,
) -> St {
    // SAFETY: as `none_of_type`.
    unsafe {
        none_of_type(
            instance,
            "fmi3SetBinary",
            valueReferences,
            nValueReferences,
            "Binary",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetClock(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    _values: *mut f3::fmi3Clock,
) -> St {
    // SAFETY: as `none_of_type`.
    unsafe {
        none_of_type(
            instance,
            "fmi3GetClock",
            valueReferences,
            nValueReferences,
            "Clock",
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetClock(
    instance: f3::fmi3Instance,
    valueReferences: *const f3::fmi3ValueReference,
    nValueReferences: usize,
    _values: *const f3::fmi3Clock,
) -> St {
    // SAFETY: as `none_of_type`.
    unsafe {
        none_of_type(
            instance,
            "fmi3SetClock",
            valueReferences,
            nValueReferences,
            "Clock",
        )
    }
}
