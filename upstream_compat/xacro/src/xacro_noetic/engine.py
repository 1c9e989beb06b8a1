"""How Noetic's xacro (1.14) walks a document, written for the pinned 1.13.3 module.

install() (in __init__) puts these functions in the place of 1.13.3's own, so the pinned module's
helpers that stay in use (parse, process_file, get_include_files, eval_extension, eval_default_arg,
replace_node, reqd_attrs, ...) call ours. What differs from 1.13.3, by upstream release:

* only `xacro:`-prefixed tags are xacro's (1.14.0); `<property>`, `<include>`, ... are plain XML;
* `xmlns:xacro` and every `xacro:*` attribute leave the output; `xacro:targetNamespace` on the
  root becomes its `xmlns` (1.13.4);
* `${` or `$(` without its closing brace is an error, not silently dropped text (1.13.5);
* `<xacro:include optional="true">` skips a missing file (1.14.1); child elements of an include
  are reported as ignored (1.14.3);
* a literal with an underscore (`1_000`, `0_5`) stays a string (1.14.4);
* a macro defined inside a macro is local to that call (1.14.7);
* macro parameter defaults may hold `${...}`, `$(...)` and quoted text with spaces (1.14.8);
* properties: `remove="true"`, `lazy_eval="false"`, a name computed by an expression, no name
  starting with '__' (1.14.10); a namespaced include sees the includer's properties, its macros
  find each other without the prefix when called from outside, and `scope="parent"` lands in the
  includer's or caller's scope (1.14.11, 1.14.13);
* a macro body's `xmlns:*` declarations move up to where it is expanded (1.14.10);
* `<!-- xacro:eval-comments -->` turns on `${...}` evaluation in the comments that follow, until
  a tag, non-blank text, the end of the element or `<!-- xacro:eval-comments:off -->` (1.14.13);
* `<xacro:arg default=...>` stores text (1.14.15);
* error locations name the macro calls being expanded (1.14.10), and a tag's unknown attributes
  are reported with the location (1.14.3).
"""
import os
import re
import sys
import xml.dom

import xacro

from . import messages, symbols

ELEMENT = xml.dom.Node.ELEMENT_NODE
TEXT = xml.dom.Node.TEXT_NODE
COMMENT = xml.dom.Node.COMMENT_NODE

# install() fills this: the names every expression sees (symbols.build_global_symbols)
GLOBAL_SYMBOLS = {}

# the macros being expanded, outermost first; left as they were when an error stops processing,
# so that the error's location lists them
macro_calls = []


def print_location():
    """Where processing is: the macro calls being expanded, then the file and its includers."""
    label = 'when instantiating macro:'
    for macro in reversed(macro_calls):
        defined_in = macro.history[-1][-1] if macro.history and macro.history[-1] else None
        print(label, macro.body.getAttribute('name'), '(%s)' % (defined_in or '???'), file=sys.stderr)
        label = 'instantiated from:'
    label = 'in file:' if macro_calls else 'when processing file:'
    for filename in reversed(xacro.filestack or []):
        print(label, filename if filename is not None else 'string', file=sys.stderr)
        label = 'included from:'


def check_attrs(tag, required, optional):
    """The values of tag's required and optional attributes; an attribute that is neither is
    reported with the location (1.14.3), then ignored."""
    values = xacro.reqd_attrs(tag, required) + xacro.opt_attrs(tag, optional)
    unknown = [a for a in tag.attributes.keys()
               if a not in required + optional and not a.startswith('xmlns:')]
    if unknown:
        messages.warning('%s: unknown attribute(s): %s' % (tag.nodeName, ', '.join(unknown)))
        if xacro.verbosity > 0:
            print_location()
    return values


class Scope(xacro.Table):
    """A property table (1.13.3's Table) with 1.14's literal rule, messages and removal."""

    @staticmethod
    def _eval_literal(value):
        if isinstance(value, str) and '_' in value:
            quoted = len(value) >= 2 and value[0] == value[-1] == "'"
            if not quoted:
                return value  # '1_000' is text here, not Python's number literal 1000
        return xacro.Table._eval_literal(value)

    def _resolve_(self, key):
        if key in self.unevaluated and key in self.recursive:
            raise xacro.XacroException(
                'circular variable definition: {}\nConsider disabling lazy evaluation via '
                'lazy_eval="false"'.format(' -> '.join(self.recursive + [key])))
        return xacro.Table._resolve_(self, key)

    def _setitem(self, key, value, unevaluated):
        if key in GLOBAL_SYMBOLS:
            messages.warning('redefining global symbol: %s' % key)
            print_location()
        value = self._eval_literal(value)
        self.table[key] = value
        if unevaluated and isinstance(value, str):
            self.unevaluated.add(key)  # evaluated at first use
        else:
            self.unevaluated.discard(key)
        if (xacro.verbosity > 2 and self.parent is None) or xacro.verbosity > 3:
            print('{}set {}: {} ({})'.format(self.depth * ' ', key, value, xacro.filestack[-1]),
                  file=sys.stderr)

    def remove(self, key):
        """Forget key here and in every enclosing scope (`<xacro:property name= remove="true"/>`)."""
        scope = self
        while scope is not None:
            scope.table.pop(key, None)
            scope.unevaluated.discard(key)
            scope = scope.parent
        if key in GLOBAL_SYMBOLS:
            messages.warning('Cannot remove global symbol: ' + key)


class PropertyNamespace(Scope):
    """The properties of `<xacro:include ns="name">`: `${name.prop}` from outside; inside, the
    includer's properties stay visible."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise NameError("name '{}' is not defined".format(name))


class MacroScope(dict):
    """Macros by name; a lookup that misses here goes on to the enclosing scope."""

    def __init__(self, parent=None):
        dict.__init__(self)
        self.parent = parent

    def __getitem__(self, name):
        if dict.__contains__(self, name):
            return dict.__getitem__(self, name)
        if self.parent is not None:
            return self.parent[name]
        raise KeyError(name)


# One token of attribute or text content; what matches none of them is an unclosed ${ or $(.
_TOKEN = re.compile(r'''
    (?P<escaped>\$\$+[{(])        # $${ or $$( : a literal ${ or $(
  | (?P<expression>\$\{[^}]*\})   # ${python expression}
  | (?P<extension>\$\([^)]*\))    # $(substitution arg)
  | (?P<text>[^$]+|\$[^{($]+|\$$) # anything else
''', re.VERBOSE)


def eval_text(text, properties):
    """Evaluate the expressions in text. One token alone keeps its type (a number stays a number);
    several are joined as text."""
    values = []
    position = 0
    while position < len(text):
        token = _TOKEN.match(text, position)
        if token is None:
            raise xacro.XacroException('invalid expression: ' + text[position:])
        position = token.end()
        piece = token.group()
        if token.lastgroup == 'expression':
            values.append(_evaluate(piece[2:-1], properties))
        elif token.lastgroup == 'extension':
            values.append(xacro.eval_extension('$(%s)' % eval_text(piece[2:-1], properties)))
        elif token.lastgroup == 'escaped':
            values.append(piece[1:])
        else:
            values.append(piece)
    if len(values) == 1:
        return values[0]
    return ''.join(str(v) for v in values)


def _evaluate(expression, properties):
    try:
        return symbols.safe_eval(eval_text(expression, properties), properties, GLOBAL_SYMBOLS)
    except Exception as e:
        raise xacro.XacroException(exc=e, suffix=os.linesep + "when evaluating expression '%s'" % expression)


def _boolean_attribute(text, default, properties):
    return xacro.get_boolean_value(eval_text(text if text is not None else default, properties), text)


def grab_property(elt, table):
    xacro.remove_previous_comments(elt)
    name, value, default, remove, scope, lazy_eval = check_attrs(
        elt, ['name'], ['value', 'default', 'remove', 'scope', 'lazy_eval'])
    name = str(eval_text(name, table))
    if not xacro.is_valid_name(name):
        raise xacro.XacroException('Property names must be valid python identifiers: ' + name)
    if name.startswith('__'):
        raise xacro.XacroException('Property names must not start with double underscore:' + name)
    remove = _boolean_attribute(remove, 'false', table)
    if sum([value is not None, default is not None, remove]) > 1:
        raise xacro.XacroException(
            'Property attributes default, value, and remove are mutually exclusive: ' + name)

    xacro.replace_node(elt, by=None)
    if remove:
        table.remove(name)
        return
    if default is not None:
        if scope is not None:
            messages.warning('%s: default property value can only be defined on local scope' % name)
        if name in table:
            return
        value = default
    if value is None:  # a block property: its content is the value
        name = '**' + name
        value = elt

    lazy = _boolean_attribute(lazy_eval, 'true', table)
    if scope == 'global':
        target = table.root()
        lazy = False
    elif scope == 'parent':
        if table.parent is None:
            messages.warning('%s: no parent scope at global scope ' % name)
            return
        target = table.parent
        lazy = False
        if not isinstance(table, PropertyNamespace):
            # in a macro: the caller's scope, past the namespaces the macro was found through
            while isinstance(target, PropertyNamespace):
                target = target.parent
    else:
        target = table
    if not lazy and isinstance(value, str):
        value = eval_text(value, table)
    target._setitem(name, value, unevaluated=lazy)


def process_include(elt, macros, properties):
    filename_spec, namespace, optional = check_attrs(elt, ['filename'], ['ns', 'optional'])
    if namespace:
        namespace = eval_text(namespace, properties)
        macros[namespace] = ns_macros = MacroScope()
        properties[namespace] = ns_properties = PropertyNamespace(parent=properties)
    else:
        ns_macros, ns_properties = macros, properties
    optional = _boolean_attribute(optional, 'false', properties)
    if xacro.first_child_element(elt):
        messages.warning('Child elements of a <xacro:include> tag are ignored')
        if xacro.verbosity > 0:
            print_location()

    included = []
    for filename in xacro.get_include_files(filename_spec, properties):
        if optional and not os.path.isfile(filename):
            continue
        outer_files = xacro.push_file(filename)
        root = xacro.parse(None, filename).documentElement
        eval_all(root, ns_macros, ns_properties)
        included.append(root)
        xacro.import_xml_namespaces(elt.parentNode, root.attributes)
        xacro.restore_filestack(outer_files)  # only on success: an error reports this file

    xacro.remove_previous_comments(elt)
    xacro.replace_node(elt, by=included, content_only=True)


# One parameter of `params`: name, then = or := , then ^ or ^| (take the caller's value), then a
# default: ${...}, $(...), or a run of quoted ('..', "..") and unquoted non-blank text; then the rest.
_PARAM_WITH_DEFAULT = re.compile(r'''
    \s*(?P<name>[^\s:=]+?)\s*:?=\s*
    (?P<forward>\^\|?)?
    (?P<default>\$\{.*?\}|\$\(.*?\)|(?:'[^']*'|"[^"]*"|[^\s'"]+)*)
    (?:\s+|$)(?P<rest>.*)
''', re.VERBOSE | re.DOTALL)


def parse_macro_arg(spec):
    """The first parameter of a macro's params: (name, (forward or None, default or None), rest),
    or (name, None, rest) when it has no default."""
    match = _PARAM_WITH_DEFAULT.match(spec)
    if match is None:
        words = spec.lstrip().split(None, 1)
        return words[0], None, words[1] if len(words) > 1 else ''
    name = match.group('name')
    forward = name if match.group('forward') else None
    return name, (forward, match.group('default') or None), match.group('rest')


def grab_macro(elt, macros):
    xacro.remove_previous_comments(elt)
    name, params = check_attrs(elt, ['name'], ['params'])
    if name == 'call':
        raise xacro.XacroException("Invalid use of macro name 'call'")
    if '.' in name:
        raise xacro.XacroException("macro names must not contain '.' (reserved for namespaces): %s" % name)
    if name.startswith('xacro:'):
        messages.warning("macro names must not contain prefix 'xacro:': %s" % name)
        name = name[len('xacro:'):]

    macro = dict.get(macros, name) or xacro.Macro()
    macro.history.append(list(xacro.filestack))
    macro.body = elt
    macro.params, macro.defaultmap = [], {}
    params = params or ''
    while params.strip():
        param, default, params = parse_macro_arg(params)
        macro.params.append(param)
        if default is not None:
            macro.defaultmap[param] = default
    macros[name] = macro
    xacro.replace_node(elt, by=None)


def resolve_macro(name, macros, properties):
    """(macros, properties, macro) for a call of name: found as is in the scopes, else as
    namespace.name, whose scopes then are the namespace's. Raises KeyError if there is none."""
    try:
        found = macros[name]
    except KeyError:
        *namespaces, name = name.split('.')
        if not namespaces:
            raise
        for namespace in namespaces:
            try:
                macros, properties = macros[namespace], properties[namespace]
            except (TypeError, AttributeError):
                raise KeyError(namespace)
        found = macros[name]
    if not isinstance(found, xacro.Macro):
        raise KeyError(name)
    return macros, properties, found


def handle_macro_call(node, macros, properties):
    if node.tagName == 'xacro:call':
        target, = xacro.reqd_attrs(node, ['macro'])
        if not target:
            raise xacro.XacroException("xacro:call is missing the 'macro' attribute")
        node.removeAttribute('macro')
        node.tagName = 'xacro:' + str(eval_text(target, properties))
    elif not node.tagName.startswith('xacro:'):
        return False
    try:
        macros, properties, macro = resolve_macro(node.tagName[len('xacro:'):], macros, properties)
    except KeyError:
        raise xacro.XacroException('unknown macro name: %s' % node.tagName)

    macro_calls.append(macro)
    body = macro.body.cloneNode(deep=True)
    local_properties = Scope(properties)
    local_macros = MacroScope(macros)
    params = macro.params[:]
    for name, value in node.attributes.items():
        if name not in params:
            raise xacro.XacroException('Invalid parameter "%s"' % name, macro=macro)
        params.remove(name)
        local_properties._setitem(name, eval_text(value, properties), unevaluated=False)
        node.setAttribute(name, '')  # already evaluated: keep eval_all below from doing it again

    eval_all(node, macros, properties)  # the blocks passed in, in the caller's scope
    block = xacro.first_child_element(node)
    for param in [p for p in params if p.startswith('*')]:
        if block is None:
            raise xacro.XacroException('Not enough blocks', macro=macro)
        params.remove(param)
        local_properties[param] = block
        block = xacro.next_sibling_element(block)
    if block is not None:
        raise xacro.XacroException('Unused block "%s"' % block.tagName, macro=macro)

    for param in [p for p in params if p in macro.defaultmap]:
        forward, default = macro.defaultmap[param]
        local_properties._setitem(
            param, xacro.eval_default_arg(forward, default, properties, macro), unevaluated=False)
        params.remove(param)
    if params:
        raise xacro.XacroException('Undefined parameters [%s]' % ','.join(params), macro=macro)

    eval_all(body, local_macros, local_properties)
    xacro.remove_previous_comments(node)
    xacro.import_xml_namespaces(node.parentNode, body.attributes)
    xacro.replace_node(node, by=body, content_only=True)
    macro_calls.pop()
    return True


def _insert_block(node, macros, properties):
    name, = check_attrs(node, ['name'], [])
    if '**' + name in properties:
        block, content_only = properties['**' + name], True
    elif '*' + name in properties:
        block, content_only = properties['*' + name], False
    else:
        raise xacro.XacroException('Undefined block "%s"' % name)
    block = block.cloneNode(deep=True)  # the same block may be inserted several times
    eval_all(block, macros, properties)
    xacro.replace_node(node, by=block, content_only=content_only)


def _declare_arg(node, properties):
    name, default = check_attrs(node, ['name', 'default'], [])
    args = xacro.substitution_args_context['arg']
    if name not in args:
        args[name] = str(eval_text(default, properties))
    xacro.remove_previous_comments(node)
    xacro.replace_node(node, by=None)


def _conditional(node, macros, properties):
    xacro.remove_previous_comments(node)
    condition, = check_attrs(node, ['value'], [])
    keep = xacro.get_boolean_value(eval_text(condition, properties), condition)
    if node.tagName == 'xacro:unless':
        keep = not keep
    if keep:
        eval_all(node, macros, properties)
        xacro.replace_node(node, by=node, content_only=True)
    else:
        xacro.replace_node(node, by=None)


def eval_all(node, macros, properties):
    """Expand node's attributes and content in place."""
    for name, value in node.attributes.items():
        if name.startswith('xacro:'):
            node.removeAttribute(name)
        else:
            node.setAttribute(name, str(eval_text(value, properties)))
    if node.hasAttribute('xmlns:xacro'):
        node.removeAttribute('xmlns:xacro')

    eval_comments = False
    child = node.firstChild
    while child:
        following = child.nextSibling
        if child.nodeType == ELEMENT:
            eval_comments = False
            tag = child.tagName
            if tag == 'xacro:insert_block':
                _insert_block(child, macros, properties)
            elif tag == 'xacro:include':
                process_include(child, macros, properties)
            elif tag == 'xacro:property':
                grab_property(child, properties)
            elif tag == 'xacro:macro':
                grab_macro(child, macros)
            elif tag == 'xacro:arg':
                _declare_arg(child, properties)
            elif tag == 'xacro:element':
                name = eval_text(xacro.reqd_attrs(child, ['xacro:name'])[0], properties)
                if not name:
                    raise xacro.XacroException('xacro:element: empty name')
                child.removeAttribute('xacro:name')
                child.nodeName = child.tagName = str(name)
                continue  # the same node again, under its new name
            elif tag == 'xacro:attribute':
                name, value = [eval_text(a, properties) for a in xacro.reqd_attrs(child, ['name', 'value'])]
                if not name:
                    raise xacro.XacroException('xacro:attribute: empty name')
                child.parentNode.setAttribute(str(name), str(value))
                xacro.replace_node(child, by=None)
            elif tag in ('xacro:if', 'xacro:unless'):
                _conditional(child, macros, properties)
            elif not handle_macro_call(child, macros, properties):
                eval_all(child, macros, properties)
        elif child.nodeType == TEXT:
            child.data = str(eval_text(child.data, properties))
            if child.data.strip():
                eval_comments = False
        elif child.nodeType == COMMENT:
            if 'xacro:eval-comments' in child.data:
                eval_comments = 'xacro:eval-comments:off' not in child.data
                xacro.replace_node(child, by=None)
            elif eval_comments:
                child.data = str(eval_text(child.data, properties))
        child = following


def process_doc(doc, mappings=None, **kwargs):
    xacro.verbosity = kwargs.get('verbosity', xacro.verbosity)
    xacro.substitution_args_context['arg'] = {} if mappings is None else mappings
    if not xacro.filestack:
        xacro.restore_filestack([None])
    del macro_calls[:]

    root = doc.documentElement
    target_namespace = root.getAttribute('xacro:targetNamespace')
    if target_namespace:
        root.removeAttribute('xacro:targetNamespace')
        root.setAttribute('xmlns', target_namespace)
    eval_all(root, MacroScope(), Scope())
    xacro.substitution_args_context['arg'] = {}
