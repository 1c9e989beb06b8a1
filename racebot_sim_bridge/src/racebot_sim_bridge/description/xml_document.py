"""XML text as TinyXML reads it, for what Gazebo and sdformat read with TinyXML (worlds, model.sdf, model.config,
spawned URDF and SDF).

Pure Python: no rospy, no pybullet. Python's parser refuses an XML declaration that is not the very first thing in
the text ("XML or text declaration not at start of entity"): a blank line before `<?xml ...?>`, or a comment
above it. TinyXML (TiXmlDocument::Parse) skips leading white space and reads a declaration wherever it stands at
the top level, so such files load in Gazebo; here the white space before the first declaration is dropped, and
a declaration that still does not open the text is left out (its encoding then is UTF-8, what nearly all say).

Text is condensed as TinyXML condenses it (TiXmlBase::condenseWhiteSpace, on by default; sdformat 9's TinyXML
2.6.2, tinyxmlparser.cpp TiXmlBase::ReadText): white space at either end of a text is dropped and every run of
white space inside it (space, tab, newline, ...) becomes one space, so `<jointName>a, b,\n  c</jointName>` reads
'a, b, c' in every plugin parameter and SDF value. A CDATA section is kept as written, as TinyXML keeps it;
attribute values are not condensed (TinyXML reads them as written). condense_white_space does it to a parsed tree
once, at the parse: fromstring and parse here, and the spawn services' and the URDF reader's parses.
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from xml.parsers import expat

__all__ = ['tinyxml_text', 'fromstring', 'parse', 'condense_white_space', 'condensed']

_DECLARATION = re.compile(rb'<\?xml\b.*?\?>', re.S)
_BOM = b'\xef\xbb\xbf'
_CDATA = '<![CDATA['
# TinyXML's IsWhiteSpace: isspace() of one byte in the C locale (not Unicode's wider set: a no-break space stays)
_WHITE_SPACE = re.compile('[ \t\n\v\f\r]+')


def tinyxml_text(data: str | bytes) -> str | bytes:
    """`data` (text or bytes) as Python's parser accepts what TinyXML accepts: white space before the first
    declaration dropped, a declaration that does not open the document left out."""
    as_text = isinstance(data, str)
    raw = data.encode('utf-8') if as_text else bytes(data)
    bom = raw.startswith(_BOM)
    body = raw[len(_BOM):] if bom else raw
    stripped = body.lstrip(b' \t\r\n')
    first = _DECLARATION.search(stripped)
    if first is None:
        return data
    if first.start() == 0:
        stripped = stripped[:first.end()] + _DECLARATION.sub(b'', stripped[first.end():])
    else:
        stripped = _DECLARATION.sub(b'', stripped)
    if stripped == body:
        return data
    if as_text:
        return stripped.decode('utf-8')
    return (_BOM if bom else b'') + stripped


def condensed(text: str | None) -> str | None:
    """`text` as TinyXML condenses a text node: white space trimmed, each run of it one space (None stays None)."""
    if text is None:
        return None
    return _WHITE_SPACE.sub(' ', text).strip(' ')


def _cdata_runs(data):
    """{(document-order index of an element, 'text' or 'tail'): [(chunk, is_cdata)]} for the texts of `data` that
    hold a CDATA section, read with expat (ElementTree joins a CDATA section into the text around it); {} when
    expat cannot read it as ElementTree did."""
    runs, where, state = {}, [None], {'count': -1, 'cdata': False, 'stack': []}

    def start(*_):
        state['count'] += 1
        state['stack'].append(state['count'])
        where[0] = (state['count'], 'text')

    def end(*_):
        where[0] = (state['stack'].pop(), 'tail')

    def chars(chunk):
        if where[0] is not None:
            runs.setdefault(where[0], []).append((chunk, state['cdata']))

    parser = expat.ParserCreate()
    parser.StartElementHandler, parser.EndElementHandler, parser.CharacterDataHandler = start, end, chars
    parser.StartCdataSectionHandler = lambda: state.update(cdata=True)
    parser.EndCdataSectionHandler = lambda: state.update(cdata=False)
    try:
        parser.Parse(data, True)
    except (expat.ExpatError, ValueError, TypeError):
        return {}
    return {key: chunks for key, chunks in runs.items() if any(is_cdata for _, is_cdata in chunks)}


def _tinyxml_nodes(chunks):
    """A text with CDATA as TinyXML reads it: its text nodes (plain text condensed, blank ones left out, CDATA as
    written), joined."""
    nodes, plain = [], []
    for chunk, is_cdata in chunks + [(None, True)]:
        if not is_cdata:
            plain.append(chunk)
            continue
        if plain and condensed(''.join(plain)):
            nodes.append(condensed(''.join(plain)))
        plain = []
        if chunk is not None:
            nodes.append(chunk)
    return ''.join(nodes)


def condense_white_space(root: ET.Element, data: str | bytes | None = None) -> ET.Element:
    """Every text and tail under `root` (changed in place, returned) condensed as TinyXML condenses text; an empty
    text becomes None, as TinyXML drops a blank text node. `data`: the text `root` was parsed from, needed only to
    keep its CDATA sections as written (without it they are condensed too)."""
    cdata = _cdata_runs(data) if data is not None and _has_cdata(data) else {}
    for index, elem in enumerate(root.iter()):
        for slot in ('text', 'tail'):
            value = getattr(elem, slot)
            if value is None:
                continue
            value = _tinyxml_nodes(cdata[(index, slot)]) if (index, slot) in cdata else condensed(value)
            setattr(elem, slot, value or None)
    root.tail = None
    return root


def _has_cdata(data):
    return (_CDATA.encode() if isinstance(data, (bytes, bytearray)) else _CDATA) in data


def fromstring(data: str | bytes) -> ET.Element:
    """ET.fromstring of tinyxml_text(data), its text condensed as TinyXML condenses it; ET.ParseError (and
    ValueError, LookupError for undecodable or unknown encodings) as ET.fromstring raises them."""
    text = tinyxml_text(data)
    return condense_white_space(ET.fromstring(text), text)


def parse(path: str) -> ET.Element:
    """The root element of the XML file at `path`, read as TinyXML reads it; OSError, ET.ParseError."""
    with open(path, 'rb') as handle:
        return fromstring(handle.read())
