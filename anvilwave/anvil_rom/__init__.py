"""Anvil geometry -> axisymmetric FE -> free-free modes -> Mode Displacement Method ROM."""

from anvilwave.anvil_rom.fem.geometry import AnvilSpec, Interfaces, Material, load_anvil
from anvilwave.anvil_rom.fem.modalfile import ModalData, load_modal_data, save_modal_data
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.inputs import InputError

__all__ = ["AnvilSpec", "Interfaces", "InputError", "Material", "ModalAnvil", "ModalData",
           "load_anvil", "load_modal_data", "save_modal_data"]
