"""Bullet's articulated warm starting, which PyBullet builds but does not offer.

Bullet's multibody solver can start each step's contact impulses from the last step's
(``SOLVER_USE_ARTICULATED_WARMSTARTING``), as its rigid-body solver does. Without it,
every step of a hand holding a ball starts from nothing: the grasp task takes 150 solver
iterations and runs at 1.7× real time on one core, Bullet's solver most of it. Warm
started, the edged hand held both balls with 30, in half the CPU time. A scene asks for it
(``Physics.warmStart``; the grasping tasks do); it is off by default because it changes
which grasps hold.

PyBullet 3.2.7 compiles Bullet's C API for it (``b3PhysicsParamSetArticulatedWarmStartingFactor``,
exported by its library) but ``setPhysicsEngineParameter`` has no argument that calls it.
Calling it needs the C handle of a PyBullet client, which lives in a table of PyBullet's
(``sPhysicsClients1``, indexed by client id) that is in the library's symbol table but not
exported. So this module finds that table from the library's file, where it lies in memory
from an exported function's address, and sends Bullet's own command for the client.
Where anything of this is missing (a stripped or different PyBullet), :func:`enable`
says so and changes nothing: the world then solves as before, needing more iterations.
"""

from __future__ import annotations

import ctypes
import functools
import logging
import struct
from dataclasses import dataclass
from typing import Any

from elftools.common.exceptions import ELFError
from elftools.elf.elffile import ELFFile

TABLE = b"sPhysicsClients1"  # pybullet.c: each connected client's C handle, by its id
ANCHOR = b"b3InitPhysicsParamCommand"  # exported: where the library lies in memory
# Elf64_Sym: name, info, other, section, value, size (what a 64-bit symbol table holds)
SYMBOL = struct.Struct("<IBBHQQ")
# The share of its last step's impulse a contact starts from: Bullet's own default (its
# m_articulatedWarmstartingFactor). At 1.0 the edged hand held 78 of 120 grasp trials at
# 40 iterations, at 0.85 87 (seed 7, 10 trials of each grip and weight).
FACTOR = 0.85

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ClientTable:
    """PyBullet's library, loaded for its C API, and where its client table lies."""

    library: ctypes.CDLL
    address: int
    clients: int  # how many handles it has room for


def enable(pybullet: Any, client: int, factor: float = FACTOR) -> bool:
    """Warm start the contacts of ``client``'s multibodies by ``factor`` (0: off again);
    False, with nothing sent, when this PyBullet does not allow it."""
    table = client_table(pybullet.__file__)
    if table is None or not 0 <= client < table.clients:
        return False
    handle = ctypes.c_void_p.from_address(table.address + client * ctypes.sizeof(ctypes.c_void_p)).value
    if not handle:  # not a connected client
        return False
    command = table.library.b3InitPhysicsParamCommand(handle)
    table.library.b3PhysicsParamSetArticulatedWarmStartingFactor(command, factor)
    table.library.b3SubmitClientCommandAndWaitStatus(handle, command)
    return True


@functools.cache
def client_table(path: str) -> ClientTable | None:
    """PyBullet's client table in this process, from its library at ``path``; None when
    the file has no symbol table or lacks either symbol."""
    found = symbols(path, (TABLE, ANCHOR))
    if len(found) < 2:
        log.warning("PyBullet at %s has no %s: contacts are not warm started, and a held "
                    "object needs more solver iterations", path, TABLE.decode())
        return None
    library = ctypes.CDLL(path)  # the same library PyBullet's import loaded: one copy in memory
    _declare(library)
    anchor = ctypes.cast(library.b3InitPhysicsParamCommand, ctypes.c_void_p).value or 0
    table, size = found[TABLE]
    return ClientTable(library, anchor - found[ANCHOR][0] + table, size // ctypes.sizeof(ctypes.c_void_p))


def symbols(path: str, names: tuple[bytes, ...]) -> dict[bytes, tuple[int, int]]:
    """Each of ``names`` found in the ELF file's symbol table: its value and size.

    pyelftools reads the file's sections; the names are then looked up in the raw tables,
    since its own lookup by name parses all of PyBullet's 16 000 symbols first (half a
    second, in every scene's process)."""
    try:
        with open(path, "rb") as file:
            elf = ELFFile(file)
            section = elf.get_section_by_name(".symtab")
            if section is None or elf.elfclass != 64 or not elf.little_endian \
                    or section["sh_entsize"] != SYMBOL.size:
                return {}
            strings = elf.get_section(section["sh_link"]).data()
            table = section.data()
    except (OSError, ELFError):  # not there, or not a library of this kind
        return {}
    wanted = {strings.find(b"\0" + name + b"\0") + 1: name for name in names}
    wanted.pop(0, None)  # a name not there
    found: dict[bytes, tuple[int, int]] = {}
    for name, _, _, _, value, size in SYMBOL.iter_unpack(table):
        if name in wanted:
            found[wanted[name]] = (value, size)
    return found


def _declare(library: ctypes.CDLL) -> None:
    """The C functions' types (ctypes would pass 64-bit handles as 32-bit ints)."""
    library.b3InitPhysicsParamCommand.argtypes = [ctypes.c_void_p]
    library.b3InitPhysicsParamCommand.restype = ctypes.c_void_p
    library.b3PhysicsParamSetArticulatedWarmStartingFactor.argtypes = [ctypes.c_void_p, ctypes.c_double]
    library.b3PhysicsParamSetArticulatedWarmStartingFactor.restype = ctypes.c_int
    library.b3SubmitClientCommandAndWaitStatus.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
    library.b3SubmitClientCommandAndWaitStatus.restype = ctypes.c_void_p
