"""Declarative, validated fields for frozen parameter dataclasses (re-export).

The implementation is the foundation module :mod:`tribolmp.params`; this
module keeps the historical import path ``tribolmp.scene.fields`` working.
"""

from __future__ import annotations

from ..params import build_dataclass, check_value, field_docs, param, validate_dataclass

__all__ = ["param", "validate_dataclass", "build_dataclass", "field_docs", "check_value"]
