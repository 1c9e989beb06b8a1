"""rospy's transport, patched for the world server: queued_publishing.py (queued publishers without a thread
switch per message) and socket_writer.pyx (the compiled writer thread they hand their messages to).

socket_writer.pyx is Cython proper: CMakeLists.txt compiles it into the devel (or install) space's copy of this
folder, which therefore comes first on this package's path; without the build queued_publishing sends from the
caller, its Python path."""
from pkgutil import extend_path

__path__ = [p for p in extend_path([], __name__) if p not in __path__] + list(__path__)
