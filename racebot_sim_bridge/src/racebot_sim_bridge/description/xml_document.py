"""XML text as TinyXML reads it, for the files Gazebo and sdformat read with TinyXML (worlds, model.sdf, model.config).

Pure Python: no rospy, no pybullet. Python's parser refuses an XML declaration that is not the very first thing in
the text ("XML or text declaration not at start of entity"): a blank line before `<?xml ...?>`, or a comment
above it. TinyXML (TiXmlDocument::Parse) skips leading white space and reads a declaration wherever it stands at
the top level, so such files load in Gazebo; here the white space before the first declaration is dropped, and
a declaration that still does not open the text is left out (its encoding then is UTF-8, what nearly all say).
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET

__all__ = ['tinyxml_text', 'fromstring', 'parse']

_DECLARATION = re.compile(rb'<\?xml\b.*?\?>', re.S)
_BOM = b'\xef\xbb\xbf'


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


def fromstring(data: str | bytes) -> ET.Element:
    """ET.fromstring of tinyxml_text(data); ET.ParseError (and ValueError, LookupError for undecodable or
    unknown encodings) as ET.fromstring raises them."""
    return ET.fromstring(tinyxml_text(data))


def parse(path: str) -> ET.Element:
    """The root element of the XML file at `path`, read as TinyXML reads it; OSError, ET.ParseError."""
    with open(path, 'rb') as handle:
        return fromstring(handle.read())
