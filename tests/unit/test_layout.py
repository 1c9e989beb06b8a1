"""The house rules of the source tree (issue 28), read from the files with `ast`, nothing imported.

- No Python module over MAX_LINES in racebot_sim_bridge/src, upstream_compat/*/src and tools: a longer one
  holds more than one job.
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
