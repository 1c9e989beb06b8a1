"""The house rules of the source tree (issue 28), read from the files with `ast`, nothing imported.

- No import runs back up a layer: the rooms of docs/ARCHITECTURE.md's ```layers block, bottom first, for every
  Python file of racebot_sim_bridge, upstream_compat, the tutorial's packages and tools/ (no exception list).
- No Python module over MAX_LINES, no class over MAX_CLASS_LINES and no function over MAX_FUNCTION_LINES in
  racebot_sim_bridge/src, upstream_compat/*/src and tools: a longer one holds more than one job.
- C and C++ only in the rooms for compiled code (CPP_ROOMS).
- No import cycle among racebot_sim_bridge's modules, nor among tools/bench's.
- description/ reads URDF and SDF without rospy and PyBullet, itself and through what it imports.
- No folder in racebot_sim_bridge is named like the real gazebo_ros or controller_manager packages.
- Every public function and method of description/ and engine/ annotates its parameters and its return.

Which imports count: every `import` statement of a module, at module level, inside functions and under
`if TYPE_CHECKING:` (imports for annotations only) alike. A function-level import runs later, so it cannot
fail at start-up (and one for annotations never runs), but the two modules still lean on each other and a
reader must untangle them just the same. None is exempt: counting them all finds no cycle in
racebot_sim_bridge, so none of its function-level imports (they defer optional or heavy dependencies:
dynamic_reconfigure, the sensor devices, the viewer process) is there to break one; a future lazy import
meant to break a cycle should rather move the shared piece. Importing `a.b.c` also runs the packages `a` and `a.b`: that
counts as an edge to each package's __init__ (but not to the importer's own packages, which are already
running). `from a.b import c` is an edge to the module a.b.c when there is one, else to the package a.b
(a name its __init__ defines). Imports built from strings (importlib) are not seen.
"""
import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PACKAGE_SRC = REPO / 'racebot_sim_bridge' / 'src'
BENCH = REPO / 'tools' / 'bench'
MAX_LINES = 700
NO_DESCRIPTION_IMPORTS = ('rospy', 'pybullet')
SHADOWED = ('gazebo_ros', 'controller_manager')
ANNOTATED = ('description', 'engine')


def _modules(root, prefix):
    """{module name: path} of the .py files below `root`, named as imported with `root` named `prefix`."""
    modules = {}
    for path in sorted(root.rglob('*.py')):
        parts = [prefix] + list(path.relative_to(root).with_suffix('').parts)
        if parts[-1] == '__init__':
            parts.pop()
        modules['.'.join(parts)] = path
    return modules


def _ancestors(name):
    """'a.b.c' -> ['a', 'a.b']."""
    parts = name.split('.')
    return ['.'.join(parts[:i]) for i in range(1, len(parts))]


def _imports(name, path, is_package):
    """[(imported module or package name, line)] of every import statement in the module, relative ones
    resolved against `name`; `from X import y` gives 'X.y' as well as 'X' (which one is real is the
    graph's business)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ''
            if node.level:
                package = name.split('.') if is_package else name.split('.')[:-1]
                package = package[:len(package) - (node.level - 1)]
                base = '.'.join(package + ([base] if base else []))
            found.append((base, node.lineno))
            found += [(base + '.' + alias.name, node.lineno) for alias in node.names]
    return found


def import_graph(modules):
    """{module: {module it imports: first line}} restricted to `modules` ({name: path})."""
    graph = {}
    for name, path in modules.items():
        is_package = path.name == '__init__.py'
        own = set(_ancestors(name)) | ({name} if is_package else set())
        edges = {}
        for target, line in _imports(name, path, is_package):
            if target.rsplit('.', 1)[0] in modules and target not in modules:
                continue  # `from pkg import name`: a name, not a module; the edge to pkg is listed separately
            for each in _ancestors(target) + [target]:
                if each in modules and each not in own and each != name:
                    edges.setdefault(each, line)
        graph[name] = edges
    return graph


def cycles(graph):
    """The strongly connected components of more than one module (Tarjan), each sorted, plus a path
    around each one for the message."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in graph[node]:
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def _loop(graph, component):
    """One import path around `component` for the message: 'a -> b (line 3) -> a (line 9)', each line number
    the importing module's."""
    members, start = set(component), component[0]
    paths = {start: [start]}
    queue = [start]
    while queue:
        node = queue.pop(0)
        for nxt, line in sorted(graph[node].items()):
            if nxt == start:
                return ' -> '.join(paths[node]) + ' -> %s (line %d)' % (start, line)
            if nxt in members and nxt not in paths:
                paths[nxt] = paths[node] + ['%s (line %d)' % (nxt, line)]
                queue.append(nxt)
    return ', '.join(component)


def _cycle_report(modules):
    graph = import_graph(modules)
    return [_loop(graph, component) for component in cycles(graph)]


# -- the layer order: read from docs/ARCHITECTURE.md, checked for every import ----------------------------

ARCHITECTURE = REPO / 'docs' / 'ARCHITECTURE.md'
# Where importable modules are found, as sys.path finds them when the product runs (catkin's devel space relays
# each package's src/ folder; the tools put tools/ first on sys.path).
IMPORT_ROOTS = ('racebot_sim_bridge/src', 'upstream_compat/*/src', 'racebot_control/src', 'racebot_gazebo/src',
                'tools')
# What the layer check reads: every Python file of the product (scripts included), not the tests or fixtures.
CHECKED = ('racebot_sim_bridge', 'upstream_compat', 'racebot_control', 'racebot_gazebo', 'tools')


def layer_rooms(text):
    """[repository path of a room] bottom first, from the ```layers block of ARCHITECTURE.md: a line's first word."""
    block = text.split('```layers\n', 1)[1].split('```', 1)[0]
    return [line.split()[0] for line in block.splitlines() if line.strip()]


def room_of(rel, rooms):
    """The index in `rooms` of the room holding the repository path `rel` (the longest room path that is a prefix of
    it: a folder ends with '/', a file is itself), or None."""
    best = None
    for index, room in enumerate(rooms):
        if (rel == room or (room.endswith('/') and rel.startswith(room))) and \
                (best is None or len(room) > len(rooms[best])):
            best = index
    return best


def importable_modules(repo):
    """{module name: repository path} of every module under IMPORT_ROOTS. Where a package and a module share a
    name, the package is what Python imports."""
    modules = {}
    for pattern in IMPORT_ROOTS:
        for root in sorted(repo.glob(pattern)):
            for path in sorted(root.rglob('*.py')):
                parts = list(path.relative_to(root).with_suffix('').parts)
                if parts[-1] == '__init__':
                    parts.pop()
                elif modules.get('.'.join(parts), '').endswith('__init__.py'):
                    continue
                if parts:
                    modules['.'.join(parts)] = str(path.relative_to(repo))
    return modules


def _resolve(target, modules):
    """The repository paths an import of `target` runs: the module itself (or the nearest package that defines
    the name) and the packages above it."""
    parts = target.split('.')
    return [modules[name] for name in ('.'.join(parts[:i]) for i in range(1, len(parts) + 1)) if name in modules]


def layer_violations(repo, rooms):
    """['file line N: imports X (room B, above room A)'] for every import in CHECKED that runs a module of a room
    listed after the importer's; plus every checked file that no room holds."""
    modules = importable_modules(repo)
    names = {path: name for name, path in modules.items()}
    found = []
    for top in CHECKED:
        for path in sorted((repo / top).rglob('*.py')):
            rel = str(path.relative_to(repo))
            if any(part in ('build', 'devel', '.venv') for part in path.relative_to(repo).parts):
                continue
            own = room_of(rel, rooms)
            if own is None:
                found.append('%s: in no room of the layer list; add its room to docs/ARCHITECTURE.md' % rel)
                continue
            name = names.get(rel, path.stem)
            for target, line in _imports(name, path, path.name == '__init__.py'):
                for target_path in _resolve(target, modules):
                    other = room_of(target_path, rooms)
                    if other is not None and other > own:
                        found.append('%s line %d: imports %s (%s, above %s)'
                                     % (rel, line, target, rooms[other], rooms[own]))
    return sorted(set(found))


def test_no_import_goes_up_a_layer():
    found = layer_violations(REPO, layer_rooms(ARCHITECTURE.read_text()))
    assert not found, ('imports that run back up a layer (docs/ARCHITECTURE.md, "Layers"): hand the lower room what '
                       'it needs, or move the shared piece down:\n' + '\n'.join(found))


def test_every_room_of_the_layer_list_exists():
    missing = [room for room in layer_rooms(ARCHITECTURE.read_text()) if not (REPO / room).exists()]
    assert not missing, 'docs/ARCHITECTURE.md lists rooms that do not exist: %s' % missing


MAX_CLASS_LINES = 300
MAX_FUNCTION_LINES = 80


def long_definitions(paths, repo):
    """['file: class C, N lines'] for classes over MAX_CLASS_LINES and functions over MAX_FUNCTION_LINES."""
    long = []
    for path in paths:
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            limit = MAX_CLASS_LINES if isinstance(node, ast.ClassDef) else \
                MAX_FUNCTION_LINES if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) else None
            count = node.end_lineno - node.lineno + 1 if limit else 0
            if limit and count > limit:
                long.append('%s: %s %s, %d lines' % (path.relative_to(repo), 'class' if limit == MAX_CLASS_LINES
                                                      else 'function', node.name, count))
    return long


def test_no_class_or_function_over_its_limit():
    roots = [PACKAGE_SRC] + sorted(REPO.glob('upstream_compat/*/src')) + [REPO / 'tools']
    long = long_definitions([path for root in roots for path in sorted(root.rglob('*.py'))], REPO)
    assert not long, ('classes over %d lines or functions over %d; split them along their jobs:\n%s'
                      % (MAX_CLASS_LINES, MAX_FUNCTION_LINES, '\n'.join(long)))


# C and C++ live in two places (docs/ARCHITECTURE.md, "Compiled code"): a stand-in for an upstream C++ package under
# upstream_compat/<its name>/ (include/ and src/), and the glue that binds C++ to the engine in racebot_sim_bridge's
# include/ and src/cpp/. Cython stays beside the Python module it compiles.
CPP_SUFFIXES = ('.c', '.cc', '.cpp', '.cxx', '.h', '.hh', '.hpp')
CPP_ROOMS = ('upstream_compat/*/include/', 'upstream_compat/*/src/', 'racebot_sim_bridge/include/',
             'racebot_sim_bridge/src/cpp/', 'tests/', 'examples/')


def misplaced_compiled_sources(repo):
    """Repository paths of C/C++ files outside CPP_ROOMS (tests/ and examples/ hold users' packages)."""
    import fnmatch
    bad = []
    for path in sorted(repo.rglob('*')):
        rel = path.relative_to(repo)
        if path.suffix not in CPP_SUFFIXES or rel.parts[0] in ('build', 'devel', '.venv', 'out', '.git'):
            continue
        if not any(fnmatch.fnmatch(str(rel), room + '*') for room in CPP_ROOMS):
            bad.append(str(rel))
    return bad


def test_compiled_code_lives_in_its_rooms():
    bad = misplaced_compiled_sources(REPO)
    assert not bad, ('C/C++ files outside the rooms for compiled code (docs/ARCHITECTURE.md, "Compiled code"):\n'
                     + '\n'.join(bad))


def test_one_name_per_class():
    """A reader who meets `Model` must know which one: no two classes of the product share a name."""
    roots = [PACKAGE_SRC, REPO / 'racebot_control' / 'src', REPO / 'racebot_gazebo' / 'src', REPO / 'tools'] + \
        sorted(REPO.glob('upstream_compat/*/src'))
    seen = {}
    for root in roots:
        for path in sorted(root.rglob('*.py')):
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                if isinstance(node, ast.ClassDef):
                    seen.setdefault(node.name, []).append(str(path.relative_to(REPO)))
    shared = ['%s: %s' % (name, ', '.join(paths)) for name, paths in sorted(seen.items()) if len(paths) > 1]
    assert not shared, 'classes sharing a name (give each one that says how it differs):\n' + '\n'.join(shared)


def test_no_module_over_the_line_limit():
    roots = [PACKAGE_SRC] + sorted(REPO.glob('upstream_compat/*/src')) + [REPO / 'tools']
    long = ['%s: %d lines' % (path.relative_to(REPO), count)
            for root in roots for path in sorted(root.rglob('*.py'))
            for count in [len(path.read_text().splitlines())] if count > MAX_LINES]
    assert not long, 'modules over %d lines; split them along their jobs:\n%s' % (MAX_LINES, '\n'.join(long))


def test_no_import_cycle_in_racebot_sim_bridge():
    found = _cycle_report(_modules(PACKAGE_SRC / 'racebot_sim_bridge', 'racebot_sim_bridge'))
    assert not found, 'import cycles (move the shared piece where it belongs):\n' + '\n'.join(found)


def test_no_import_cycle_in_tools_bench():
    found = _cycle_report(_modules(BENCH, 'bench'))
    assert not found, 'import cycles (move the shared piece where it belongs):\n' + '\n'.join(found)


def test_description_needs_neither_rospy_nor_pybullet():
    """Directly or through the racebot_sim_bridge modules it imports."""
    modules = _modules(PACKAGE_SRC / 'racebot_sim_bridge', 'racebot_sim_bridge')
    graph = import_graph(modules)
    bad = []
    for name in sorted(modules):
        if not name.startswith('racebot_sim_bridge.description'):
            continue
        seen, todo, via = {name}, [name], {name: name}
        while todo:
            node = todo.pop()
            path = modules[node]
            for target, line in _imports(node, path, path.name == '__init__.py'):
                if target.split('.')[0] in NO_DESCRIPTION_IMPORTS:
                    bad.append('%s imports %s (%s line %d)' % (via[node], target, path.relative_to(REPO), line))
            for nxt in graph[node]:
                if nxt not in seen:
                    seen.add(nxt)
                    via[nxt] = '%s through %s' % (name, nxt)
                    todo.append(nxt)
    assert not bad, 'description/ must stay free of rospy and PyBullet:\n' + '\n'.join(sorted(set(bad)))


def test_no_folder_shadows_upstream_packages():
    shadows = [str(path.relative_to(REPO)) for path in sorted((REPO / 'racebot_sim_bridge').rglob('*'))
               if path.is_dir() and path.name in SHADOWED]
    assert not shadows, ('folders named like the real %s Python packages (one on sys.path hides them, a nested '
                         'one misleads a reader):\n%s'
                         % (' and '.join(SHADOWED), '\n'.join(shadows)))


def _public_functions(tree):
    """(qualified name, def node, is a method) of the public functions of a module: module-level ones and the
    methods of its classes (nested classes too), each name not starting with '_' (and the class names
    along the way neither); `__init__` counts, the other dunder methods do not."""
    def walk(body, prefix, in_class):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if not node.name.startswith('_') or (in_class and node.name == '__init__'):
                    yield prefix + node.name, node, in_class
            elif isinstance(node, ast.ClassDef) and not node.name.startswith('_'):
                yield from walk(node.body, prefix + node.name + '.', True)
    return walk(tree.body, '', False)


def _missing_annotations(path):
    """['name(line): what is missing'] for the public functions of the module at `path`."""
    missing = []
    for name, node, is_method in _public_functions(ast.parse(path.read_text(), str(path))):
        args = node.args
        params = args.posonlyargs + args.args
        static = any(isinstance(d, ast.Name) and d.id == 'staticmethod' for d in node.decorator_list)
        if is_method and not static and params:
            params = params[1:]  # self or cls
        params = params + args.kwonlyargs + [a for a in (args.vararg, args.kwarg) if a]
        unannotated = [p.arg for p in params if p.annotation is None]
        gaps = (['parameters ' + ', '.join(unannotated)] if unannotated else []) + \
            (['return'] if node.returns is None else [])
        if gaps:
            missing.append('%s (line %d): %s' % (name, node.lineno, ' and '.join(gaps)))
    return missing


def test_public_functions_of_description_and_engine_are_annotated():
    """Parameters (but self and cls) and return alike, so a reader sees what goes in and out."""
    package = PACKAGE_SRC / 'racebot_sim_bridge'
    bad = ['%s: %s' % (path.relative_to(REPO), gap) for folder in ANNOTATED
           for path in sorted((package / folder).rglob('*.py')) for gap in _missing_annotations(path)]
    assert not bad, 'public functions without type annotations:\n' + '\n'.join(bad)


# -- the checks themselves, on made-up trees -------------------------------------------------------------


def _tree(tmp_path, files):
    for rel, text in files.items():
        path = tmp_path / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return _modules(tmp_path / 'pkg', 'pkg')


def test_a_cycle_through_a_function_level_import_is_found(tmp_path):
    modules = _tree(tmp_path, {'pkg/__init__.py': '', 'pkg/a.py': 'from pkg import b\n',
                               'pkg/b.py': 'def f():\n    from . import a\n'})
    assert _cycle_report(modules) == ['pkg.a -> pkg.b (line 1) -> pkg.a (line 2)']


def test_a_package_init_importing_a_module_that_imports_it_back_is_a_cycle(tmp_path):
    modules = _tree(tmp_path, {'pkg/__init__.py': '', 'pkg/sub/__init__.py': 'from pkg.sub.m import X\n',
                               'pkg/sub/m.py': 'X = 1\n', 'pkg/other.py': 'from pkg.sub import X\n'})
    assert _cycle_report(modules) == []  # other -> sub -> m: no way back
    (tmp_path / 'pkg/sub/m.py').write_text('from pkg.other import Y\nX = 1\n')
    assert _cycle_report(modules) == ['pkg.other -> pkg.sub (line 1) -> pkg.sub.m (line 1) -> pkg.other (line 1)']


def test_a_sibling_import_through_the_own_package_is_no_cycle(tmp_path):
    modules = _tree(tmp_path, {'pkg/__init__.py': 'from pkg import a\n', 'pkg/a.py': 'from pkg import b\n',
                               'pkg/b.py': 'import pkg.c\n', 'pkg/c.py': ''})
    assert _cycle_report(modules) == []


def test_a_missing_annotation_is_named(tmp_path):
    path = tmp_path / 'm.py'
    path.write_text('def f(a: int, *, b) -> int:\n    pass\n'
                    'def _g(x):\n    pass\n'
                    'class C:\n'
                    '    def __init__(self, x: int):\n        pass\n'
                    '    def __eq__(self, other):\n        pass\n'
                    '    @staticmethod\n    def s(v) -> None:\n        pass\n'
                    '    @classmethod\n    def c(cls) -> None:\n        pass\n'
                    '    def _p(self, y):\n        pass\n'
                    'class _Hidden:\n    def m(self, z):\n        pass\n')
    assert _missing_annotations(path) == ['f (line 1): parameters b', 'C.__init__ (line 6): return',
                                          'C.s (line 11): parameters v']


def test_an_import_up_a_layer_is_found_and_one_down_is_not(tmp_path):
    package = 'racebot_sim_bridge/src/racebot_sim_bridge/'
    rooms = ['racebot_sim_bridge/', package + 'engine/', package + 'sensors/', 'tools/']
    files = {'racebot_sim_bridge/src/racebot_sim_bridge/__init__.py': '',
             'racebot_sim_bridge/src/racebot_sim_bridge/engine/__init__.py': '',
             'racebot_sim_bridge/src/racebot_sim_bridge/engine/world.py': 'import math\n',
             'racebot_sim_bridge/src/racebot_sim_bridge/sensors/__init__.py': '',
             package + 'sensors/ray.py': 'from racebot_sim_bridge.engine import world\n',
             'tools/bench/__init__.py': '', 'tools/bench/run.py': 'from racebot_sim_bridge.sensors.ray import x\n'}
    for rel, text in files.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(text)
    assert layer_violations(tmp_path, rooms) == []
    (tmp_path / package / 'engine/world.py').write_text('def f():\n    from racebot_sim_bridge.sensors import ray\n')
    assert layer_violations(tmp_path, rooms) == [
        'racebot_sim_bridge/src/racebot_sim_bridge/engine/world.py line 2: imports racebot_sim_bridge.sensors '
        '(racebot_sim_bridge/src/racebot_sim_bridge/sensors/, above racebot_sim_bridge/src/racebot_sim_bridge/engine/)',
        'racebot_sim_bridge/src/racebot_sim_bridge/engine/world.py line 2: imports racebot_sim_bridge.sensors.ray '
        '(racebot_sim_bridge/src/racebot_sim_bridge/sensors/, above racebot_sim_bridge/src/racebot_sim_bridge/engine/)']
    (tmp_path / 'tools/loose.py').parent.mkdir(exist_ok=True)
    assert room_of('tools/loose.py', rooms) == 3 and room_of('upstream_compat/x.py', rooms) is None


def test_the_layer_list_is_read_from_its_block():
    text = 'x\n```layers\na/b/   one\n\nc.py  two words\n```\n```layers\nz/\n```'
    assert layer_rooms(text) == ['a/b/', 'c.py']


def test_a_long_class_and_a_long_function_are_named(tmp_path):
    path = tmp_path / 'm.py'
    path.write_text('class C:\n' + '    x = 1\n' * 300 + 'def f():\n' + '    y = 1\n' * 80)
    assert long_definitions([path], tmp_path) == ['m.py: class C, 301 lines', 'm.py: function f, 81 lines']


def test_a_cpp_file_outside_its_rooms_is_named(tmp_path):
    for rel in ('racebot_sim_bridge/src/racebot_sim_bridge/engine/fast.cpp', 'upstream_compat/gazebo_dev/include/'
                'gazebo/gazebo.hh', 'racebot_sim_bridge/src/cpp/plugin_host.cpp', 'tests/fixtures/p/src/a.cc'):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text('')
    assert misplaced_compiled_sources(tmp_path) == ['racebot_sim_bridge/src/racebot_sim_bridge/engine/fast.cpp']
