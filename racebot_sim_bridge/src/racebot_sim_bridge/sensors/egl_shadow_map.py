"""Switches off the shadow-map pass that PyBullet's EGL renderer plugin runs on every frame.

The plugin's GLInstancingRenderer renders a shadow map of the whole scene (a depth pass from its
light) before each camera frame, whatever getCameraImage's `shadow` argument says (only the TinyRenderer reads it),
and no PyBullet call reaches it (configureDebugVisualizer(COV_ENABLE_SHADOWS) goes to the GUI's
renderer, not the plugin's). The switch is the plugin's global `bool useShadowMap`, which the
shared object does not export. Measured on llvmpipe, 2 cores: an 800 x 800 frame 69 -> 26 ms, a
640 x 480 frame 55 -> 14 ms. Neither renderer then draws shadows (the simulator asks for shadow=0
everywhere; the pass's light was PyBullet's, not the world's sun), and a sunlit face gets the
TinyRenderer's colour: (114, 152, 72) in both in one scene, (103, 137, 65) with the pass.

How: the flag's offset and that of the exported `PyInit_eglRenderer` are read from the file's
ELF symbol table (pyelftools); dlopen of the same file returns the already-loaded plugin, whose
PyInit_eglRenderer address less its offset is the load address. The flag is written only when the
symbol table has both symbols, the flag is a one-byte object and it reads 0 or 1, as a bool must;
otherwise nothing is written, ShadowMapError says why, and frames keep their shadow pass (correct,
slower).
"""
import ctypes

FLAG = 'useShadowMap'
ANCHOR = 'PyInit_eglRenderer'  # exported: its runtime address gives the load address


class ShadowMapError(RuntimeError):
    """The flag could not be found or did not look like the plugin's shadow-map switch."""


def symbol_offsets(path, names):
    """{name: (offset, size, 'STT_OBJECT' or 'STT_FUNC')} of those of the named symbols found in the
    ELF file's symbol tables (.symtab and .dynsym)."""
    from elftools.common.exceptions import ELFError
    from elftools.elf.elffile import ELFFile
    from elftools.elf.sections import SymbolTableSection
    found = {}
    try:
        with open(path, 'rb') as f:
            elf = ELFFile(f)
            for section in elf.iter_sections():
                if not isinstance(section, SymbolTableSection):
                    continue
                for name in names:
                    if name in found:
                        continue
                    symbols = section.get_symbol_by_name(name) or []
                    for symbol in symbols:
                        if symbol['st_value'] and symbol['st_info']['type'] in ('STT_OBJECT', 'STT_FUNC'):
                            found[name] = (symbol['st_value'], symbol['st_size'], symbol['st_info']['type'])
                            break
    except (OSError, ELFError) as err:
        raise ShadowMapError('cannot read %s: %s' % (path, err))
    return found


def flag_of(path):
    """ctypes.c_bool over the loaded plugin's `useShadowMap` (the plugin at `path` must be loaded)."""
    offsets = symbol_offsets(path, (FLAG, ANCHOR))
    missing = [n for n in (FLAG, ANCHOR) if n not in offsets]
    if missing:
        raise ShadowMapError('%s has no symbol %s (a stripped or different PyBullet build)'
                             % (path, ', '.join(missing)))
    flag_offset, flag_size, flag_type = offsets[FLAG]
    if flag_type != 'STT_OBJECT' or flag_size != ctypes.sizeof(ctypes.c_bool):
        raise ShadowMapError('%s: %s is not a one-byte variable' % (path, FLAG))
    try:
        library = ctypes.CDLL(path)  # the plugin PyBullet loaded: dlopen hands back the same object
        anchor = ctypes.cast(getattr(library, ANCHOR), ctypes.c_void_p).value
    except (OSError, AttributeError) as err:
        raise ShadowMapError('cannot open %s: %s' % (path, err))
    base = anchor - offsets[ANCHOR][0]
    return ctypes.c_bool.from_address(base + flag_offset)


def switch_off(path):
    """Switches the loaded EGL plugin's shadow-map pass off. Raises ShadowMapError when it cannot
    (nothing written)."""
    byte = ctypes.c_uint8.from_address(ctypes.addressof(flag_of(path)))
    if byte.value not in (0, 1):
        raise ShadowMapError('%s: %s holds %d, not a bool; left alone' % (path, FLAG, byte.value))
    byte.value = 0


def is_on(path):
    return bool(flag_of(path).value)
