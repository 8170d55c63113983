//! A serde [`Deserializer`] over Python plain data, so that run settings enter the core the way
//! TOML and JSON do: `RunSettingsDesc::deserialize(PyData(obj))`. Dicts are maps, lists, tuples
//! and numpy arrays are sequences (a float64 array is read as one block, not element by
//! element), `None` is unit or an absent option, and `float('inf')` stays infinite (JSON, the
//! description's route, has no ∞; a wall-time budget or an error limit may be one).

use std::fmt;

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};
use serde::de::{self, DeserializeSeed, IntoDeserializer, MapAccess, SeqAccess, Visitor};
use serde::forward_to_deserialize_any;

/// Why Python data did not fit the expected type.
#[derive(Debug)]
pub(super) struct DeError(String);

impl fmt::Display for DeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DeError {}

impl de::Error for DeError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        DeError(msg.to_string())
    }
}

fn py_err(e: PyErr) -> DeError {
    DeError(e.to_string())
}

/// One Python object, to be deserialised.
pub(super) struct PyData<'py>(pub Bound<'py, PyAny>);

impl<'de, 'py> de::Deserializer<'de> for PyData<'py> {
    type Error = DeError;

    fn deserialize_any<V: Visitor<'de>>(self, v: V) -> Result<V::Value, DeError> {
        let o = self.0;
        if o.is_none() {
            return v.visit_unit();
        }
        if let Ok(b) = o.cast::<PyBool>() {
            return v.visit_bool(b.is_true());
        }
        if o.cast::<PyInt>().is_ok() {
            return match o.extract::<i64>() {
                Ok(i) => v.visit_i64(i),
                Err(_) => v.visit_u64(o.extract::<u64>().map_err(py_err)?),
            };
        }
        if let Ok(f) = o.cast::<PyFloat>() {
            return v.visit_f64(f.value());
        }
        if let Ok(s) = o.cast::<PyString>() {
            return v.visit_string(s.extract::<String>().map_err(py_err)?);
        }
        if let Ok(d) = o.cast::<PyDict>() {
            let items: Vec<_> = d.iter().collect();
            return v.visit_map(DictItems { items: items.into_iter(), value: None });
        }
        if let Ok(a) = o.extract::<PyReadonlyArray1<f64>>() {
            let values = a.as_slice().map(|s| s.to_vec()).unwrap_or_else(|_| a.as_array().to_vec());
            return v.visit_seq(Floats(values.into_iter()));
        }
        if o.hasattr("tolist").map_err(py_err)? && !o.is_instance_of::<PyList>() {
            // Other numpy arrays and numpy scalars: as Python lists and numbers.
            return PyData(o.call_method0("tolist").map_err(py_err)?).deserialize_any(v);
        }
        if let Ok(it) = o.try_iter() {
            let items = it.collect::<PyResult<Vec<_>>>().map_err(py_err)?;
            return v.visit_seq(Items(items.into_iter()));
        }
        let repr = o.repr().map(|r| r.to_string()).unwrap_or_default();
        Err(de::Error::custom(format!("{repr} is not plain data (dicts, lists, numbers, strings)")))
    }

    fn deserialize_option<V: Visitor<'de>>(self, v: V) -> Result<V::Value, DeError> {
        if self.0.is_none() {
            v.visit_none()
        } else {
            v.visit_some(self)
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(self, _name: &'static str, _variants: &'static [&'static str], v: V) -> Result<V::Value, DeError> {
        // Unit variants, named by a string.
        let s: String = self.0.extract().map_err(|_| de::Error::custom("expected a string"))?;
        v.visit_enum(s.into_deserializer())
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf unit
        unit_struct newtype_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

struct DictItems<'py> {
    items: std::vec::IntoIter<(Bound<'py, PyAny>, Bound<'py, PyAny>)>,
    value: Option<Bound<'py, PyAny>>,
}

impl<'de, 'py> MapAccess<'de> for DictItems<'py> {
    type Error = DeError;
    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, DeError> {
        match self.items.next() {
            Some((k, v)) => {
                self.value = Some(v);
                seed.deserialize(PyData(k)).map(Some)
            }
            None => Ok(None),
        }
    }
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, DeError> {
        let v = self.value.take().ok_or_else(|| de::Error::custom("a value without its key"))?;
        seed.deserialize(PyData(v))
    }
}

struct Items<'py>(std::vec::IntoIter<Bound<'py, PyAny>>);

impl<'de, 'py> SeqAccess<'de> for Items<'py> {
    type Error = DeError;
    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, DeError> {
        self.0.next().map(|o| seed.deserialize(PyData(o))).transpose()
    }
}

struct Floats(std::vec::IntoIter<f64>);

impl<'de> SeqAccess<'de> for Floats {
    type Error = DeError;
    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, DeError> {
        self.0.next().map(|x| seed.deserialize(x.into_deserializer())).transpose()
    }
    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}
