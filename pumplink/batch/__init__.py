"""Batch runs over design variants: batch files (:mod:`~pumplink.batch.files`) and their
evaluation in chunks on any executor (:mod:`~pumplink.batch.run`)."""

from pumplink.batch.files import (
    FAIL_CHECKS,
    INERTIA_KEYS,
    MAX_AXIS_VALUES,
    MAX_VARIANTS,
    VARIABLE_KEYS,
    Axis,
    Batch,
    axis_indices,
    is_batch_mapping,
    load_batch,
    load_inputs,
    parse_batch,
    parse_chunk,
    parse_fail_on,
    spec_batch,
    variant_name,
    variant_names,
    variant_spec,
)
from pumplink.batch import run as run_module
from pumplink.batch.run import (
    CHUNK_DESIGNS,
    FLYWHEEL_DESIGNS,
    FLYWHEEL_LABEL,
    QUASI_STATIC_LABEL,
    SUB_DESIGNS,
    TASK_SAMPLES,
    Chunk,
    evaluate_chunk,
    plan,
    run,
)

__all__ = [
    "CHUNK_DESIGNS", "FAIL_CHECKS", "FLYWHEEL_DESIGNS", "FLYWHEEL_LABEL", "QUASI_STATIC_LABEL", "INERTIA_KEYS", "MAX_AXIS_VALUES", "MAX_VARIANTS",
    "SUB_DESIGNS", "TASK_SAMPLES", "VARIABLE_KEYS", "Axis", "Batch", "Chunk", "axis_indices", "evaluate_chunk",
    "is_batch_mapping", "load_batch", "load_inputs", "parse_batch", "parse_chunk", "parse_fail_on", "plan", "run",
    "spec_batch", "variant_name", "variant_names", "variant_spec",
]
