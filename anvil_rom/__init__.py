"""Anvil geometry -> axisymmetric FE -> free-free modes -> Mode Displacement Method ROM."""

from anvilwave_inputs import InputError

from .geometry import AnvilSpec, Interfaces, Material, load_anvil
from .modalfile import ModalData, load_modal_data, save_modal_data
from .rom import ModalAnvil

__all__ = ["AnvilSpec", "Interfaces", "InputError", "Material", "ModalAnvil", "ModalData",
           "load_anvil", "load_modal_data", "save_modal_data"]
