"""export_materials(): Blender materials -> one .mgraph per material (the public API).

    from memograph_export import exporter
    result = exporter.export_materials(bpy.data.materials, '/tmp/out')
    result.files     # paths written, in material order
    result.warnings  # [(material name, node label, message)]
    result.errors    # [(material name, message)]: materials that could not be written

Also writes <out>/index.json: {"materials": {blender name: {"file", "material"}}} (the
mapping from Blender's material names to the sanitized mgraph names) and copies images to
<out>/textures/. Every file is written atomically (a temp file, then os.replace).
"""

import json
import os
import shutil

from . import compat, graph, lobes, shaders, writers
from .graph import Const, Convert, Out, ExportError, FLOAT, VECTOR, COLOR, SHADER
from .mgraph import GraphBuilder, Link, Literal, sanitize_identifier


class ExportResult:
    def __init__(self):
        self.files = []
        self.warnings = []
        self.errors = []
        self.names = {}  # blender material name -> mgraph material name

    def __repr__(self):
        return 'ExportResult(files=%d, warnings=%d, errors=%d)' % (
            len(self.files), len(self.warnings), len(self.errors))


def write_atomic(path, data):
    """Writes bytes or text to path through a temp file and os.replace."""
    tmp = path + '.tmp%d' % os.getpid()
    mode = 'wb' if isinstance(data, bytes) else 'w'
    kw = {} if isinstance(data, bytes) else {'encoding': 'utf-8', 'newline': '\n'}
    with open(tmp, mode, **kw) as f:
        f.write(data)
    os.replace(tmp, path)


class Assets:
    """Images copied/unpacked next to the graphs: textures/<name>.<ext>, one per image."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self._paths = {}
        self._used_names = set()

    def image_path(self, image, warn):
        if image.name in self._paths:
            return self._paths[image.name]
        ext = _image_ext(image)
        stem = sanitize_identifier(os.path.splitext(image.name)[0]) or 'image'
        name = stem + ext
        n = 1
        while name in self._used_names:
            n += 1
            name = '%s_%d%s' % (stem, n, ext)
        self._used_names.add(name)
        rel = 'textures/' + name
        dest = os.path.join(self.out_dir, 'textures', name)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        try:
            if image.packed_file is not None:
                write_atomic(dest, bytes(image.packed_file.data))
            elif image.source == 'FILE' and image.filepath:
                import bpy  # only here: resolves '//' paths against the .blend
                src = bpy.path.abspath(image.filepath, library=image.library)
                if not os.path.isfile(src):
                    warn('image file %s is missing: the texture is not carried' % src)
                    return None
                tmp = dest + '.tmp%d' % os.getpid()
                shutil.copyfile(src, tmp)
                os.replace(tmp, dest)
            elif image.source == 'GENERATED' or image.has_data:
                # Generated or painted in Blender and never saved: write its pixels as they
                # are held (Image.save writes raw data, no view transform), from a copy so
                # the user's image keeps its settings.
                copy = image.copy()
                try:
                    tmp = dest + '.tmp%d%s' % (os.getpid(), ext)
                    copy.filepath_raw = tmp
                    copy.file_format = {'.exr': 'OPEN_EXR', '.png': 'PNG'}.get(ext, 'PNG')
                    copy.save()
                    os.replace(tmp, dest)
                finally:
                    import bpy
                    bpy.data.images.remove(copy)
            else:
                warn('image %s (source %s) is neither a file nor packed: not carried'
                     % (image.name, image.source))
                return None
        except OSError as exc:
            warn('cannot write image %s: %s' % (image.name, exc))
            return None
        self._paths[image.name] = rel
        return rel


def _image_ext(image):
    path = image.filepath_raw or image.filepath or ''
    ext = os.path.splitext(path)[1].lower()
    if ext:
        return ext
    if image.source == 'GENERATED':
        return '.exr' if image.is_float else '.png'
    fmt = getattr(image, 'file_format', 'PNG')
    return {'PNG': '.png', 'OPEN_EXR': '.exr', 'JPEG': '.jpg', 'TARGA': '.tga',
            'HDR': '.hdr', 'TIFF': '.tif'}.get(fmt, '.png')


class MaterialWriter:
    """Writes one material: operands for sources, node writers on demand, warnings."""

    def __init__(self, material, table, assets, result):
        self.material = material
        self.table = table
        self.assets = assets
        self.result = result
        self.builder = GraphBuilder()
        self.walker = graph.Walker(self._walker_warn)
        self._written = {}  # flat key -> {output identifier: Link}
        self._converted = {}
        self._implicit = {}
        self._warned = set()
        self.usage = {}  # flat key -> output identifiers some consumer reads

    # warnings -------------------------------------------------------------------------
    def warn(self, flat, message):
        label = flat if isinstance(flat, str) else flat.label
        key = (label, message)
        if key in self._warned:
            return
        self._warned.add(key)
        self.result.warnings.append((self.material.name, label, message))

    def _walker_warn(self, label, message):
        self.warn(label, message)

    def warn_material(self, message):
        self.warn('', message)

    # operands -------------------------------------------------------------------------
    def input_operand(self, flat, identifier):
        src = flat.input(identifier)
        if src is None:
            return None
        return self.operand(src)

    def operand(self, src):
        """Link or Literal for a value Source (Const / Out / Convert)."""
        if src is None:
            return None
        if isinstance(src, Const):
            if src.kind == SHADER or src.kind is None or src.value is None:
                return None
            return Literal(src.value)
        if isinstance(src, Convert):
            if src.op in ('splat', 'retag'):
                return self.operand(src.source)
            if src.op in ('luminance', 'average'):
                inner = self.operand(src.source)
                key = (src.op, _source_key(src.source))
                if key[1] is not None and key in self._converted:
                    return self._converted[key]
                link = self.builder.new_link()
                if src.op == 'luminance':
                    self.builder.add('RGBToBW', [('Color', inner)], [('Val', link)],
                                     comment='implicit colour -> float')
                else:
                    self.builder.add('VectorAverage', [('Vector', inner)], [('Value', link)],
                                     comment='implicit vector -> float')
                if key[1] is not None:
                    self._converted[key] = link
                return link
            return self.operand(src.source)
        if isinstance(src, Out):
            return self.node_output(src)
        raise TypeError(src)

    def node_output(self, out):
        flat = out.node
        if out.kind == SHADER:
            return None
        links = self._written.get(flat.key)
        if links is None:
            links = self._write_node(flat)
            self._written[flat.key] = links
        link = links.get(out.identifier)
        if link is not None:
            return link
        default = graph._as_value(getattr(out.socket, 'default_value', None), out.kind)
        if flat.bl_idname in self.table or flat.bl_idname in shaders.SHADER_WRITERS:
            self.warn(flat, 'output %r is not carried: its default %s is used instead'
                      % (out.socket.name, shaders._fmt(default)))
        return Literal(default)

    def _write_node(self, flat):
        writer = self.table.get(flat.bl_idname)
        if writer is None:
            used = self.usage.get(flat.key, ())
            for socket in flat.node.outputs:
                if socket.identifier in used:
                    kind = graph.socket_kind(socket)
                    default = graph._as_value(getattr(socket, 'default_value', None), kind)
                    self.warn(flat, 'node type %s (%s) is not supported: its output %r is '
                              'replaced by the default value %s'
                              % (flat.bl_idname, flat.node.bl_label, socket.name,
                                 shaders._fmt(default)))
            return {}
        for message in compat.version_warnings(flat.node):
            self.warn(flat, message)
        compat.check_new_inputs(
            flat.node, lambda ident: (flat.is_linked(ident), getattr(flat.input(ident),
                                                                     'value', None)),
            lambda msg: self.warn(flat, msg),
            carried=getattr(getattr(writer, 'spec', None), 'inputs', {}))
        return writer(self, flat, self.usage.get(flat.key, set()))

    def implicit(self, which):
        """Blender's implicit coordinates for an unlinked Vector input."""
        if which in self._implicit:
            return self._implicit[which]
        link = self.builder.new_link()
        if which in ('uv', 'uv2'):
            # UVInput (float2, z = 0 when widened), not TextureCoordinate: it reads only the
            # UV, so the material stays cacheable.
            self.builder.add('UVInput', [], [('Out', link)], comment='implicit UV')
        elif which == 'normal':
            self.builder.add('NormalInput', [], [('Out', link)], comment='implicit normal')
        elif which == 'position':
            self.builder.add('PositionInput', [], [('Out', link)], comment='implicit position')
        else:
            socket = {'generated': 'Generated', 'object': 'Object'}[which]
            self.builder.add('TextureCoordinate', [], [(socket, link)],
                             comment='implicit %s coordinates' % which)
        self._implicit[which] = link
        return link

    def shader(self, source):
        return shaders.evaluate(self, source)

    # the material -------------------------------------------------------------------
    def write(self, header):
        mat = self.material
        self.builder.comment(header)
        tree = mat.node_tree if mat.use_nodes else None
        library = missing_library(mat)
        if library is not None or tree is None:
            if library is not None:
                # A placeholder: Blender read nothing of the material but its name.
                self.warn('', 'the material is linked from the library %s, which is '
                          'missing: its placeholder\'s viewport colour, metallic and '
                          'roughness are written' % library)
            else:
                self.warn('', 'material does not use nodes: its viewport colour, metallic '
                          'and roughness are written')
            shaders.write_outputs(self, shaders.Params(
                base_color=Literal(tuple(mat.diffuse_color)[:3]),
                metallic=Literal(float(mat.metallic)),
                roughness=Literal(float(mat.roughness))))
            return self.builder.text()
        out_node = graph.find_output_node(tree)
        if out_node is None:
            raise ExportError('no Material Output node (target All or Cycles)')
        ctx = graph.TreeContext(tree)
        root = self.walker.flat(ctx, out_node)
        self.usage = {}
        _collect_usage(root, self.usage, set())
        for name in ('Volume', 'Displacement'):
            if root.is_linked(name):
                self.warn(root, '%s is linked but not carried: ignored' % name)
        surface = root.input('Surface')
        if surface is None or isinstance(surface, Const):
            self.warn(root, 'Surface is not linked: Cycles renders black, which is written')
        if lobes.writes_lobes(self, surface):  # BSDFs, mixed Principled, Mix/Add: exact
            lobes.write(self, surface)
            return self.builder.text()
        params = shaders.evaluate(self, surface)
        shaders.write_outputs(self, params)
        return self.builder.text()


def _source_key(src):
    if isinstance(src, Out):
        return (src.node.key, src.identifier)
    if isinstance(src, Convert):
        inner = _source_key(src.source)
        return None if inner is None else (src.op, inner)
    return None


def _collect_usage(flat, usage, visited):
    """Marks, for every node reachable from flat, which outputs some consumer reads."""
    if flat.key in visited:
        return
    visited.add(flat.key)
    for socket in flat.enabled_inputs():
        src = flat.input(socket.identifier)
        while isinstance(src, Convert):
            src = src.source
        if isinstance(src, Out):
            usage.setdefault(src.node.key, set()).add(src.identifier)
            _collect_usage(src.node, usage, visited)


def missing_library(material):
    """'NAME' (PATH) of the library a linked material should come from when that library is
    missing (Blender then keeps a placeholder without nodes), else None."""
    library = getattr(material, 'library', None)
    if library is None:
        return None
    path = getattr(library, 'filepath', '')
    try:
        import bpy
        absolute = bpy.path.abspath(path, library=getattr(library, 'library', None))
    except ImportError:
        absolute = path
    if not getattr(material, 'is_missing', False) and os.path.exists(absolute):
        return None
    return '%r (%s)' % (library.name, absolute)


def newer_file_warning(file_version, running_file_version, running_name):
    """The warning for a .blend saved by a newer Blender than the running one, else None.
    Versions are (major, minor, file subversion): bpy.data.version, bpy.app.version_file."""
    if tuple(file_version) <= tuple(running_file_version):
        return None
    return ('saved by Blender %d.%d (file version %d.%d.%d), newer than the running Blender '
            '%s: results may differ (nodes, settings and defaults that this Blender does '
            'not know are read as it can, or dropped by Blender itself)'
            % (file_version[0], file_version[1], file_version[0], file_version[1],
               file_version[2], running_name))


def _header(material):
    try:
        import bpy
        blend = bpy.data.filepath or '(unsaved)'
        version = bpy.app.version_string
    except ImportError:
        blend, version = '(none)', '(none)'
    return ('Exported by memograph_export from %s, material "%s" (Blender %s).\n'
            'Do not edit: re-export instead.' % (os.path.basename(blend), material.name,
                                                version))


def unique_names(materials):
    """{blender name: mgraph name}: sanitized, unique (suffix _2, _3 ... in input order)."""
    names = {}
    taken = set()
    for mat in materials:
        base = sanitize_identifier(mat.name)
        name = base
        n = 1
        while name.lower() in taken:
            n += 1
            name = '%s_%d' % (base, n)
        taken.add(name.lower())
        names[mat.name] = name
    return names


def export_materials(materials, out_dir, table=None):
    """Writes one .mgraph per material into out_dir. Returns an ExportResult.

    A material that cannot be exported at all (no output node, a recursive group) is
    reported in result.errors; the others are still written.
    """
    materials = [m for m in materials if m is not None and not getattr(m, 'is_grease_pencil',
                                                                      False)]
    os.makedirs(out_dir, exist_ok=True)
    if table is None:
        table = writers.build_table()
    result = ExportResult()
    assets = Assets(out_dir)
    result.names = unique_names(materials)
    index = {}
    for mat in materials:
        name = result.names[mat.name]
        mw = MaterialWriter(mat, table, assets, result)
        try:
            body = mw.write(_header(mat))
        except ExportError as exc:
            result.errors.append((mat.name, str(exc)))
            continue
        except Exception as exc:  # a bug here: report it, export the other materials
            import traceback
            traceback.print_exc()
            result.errors.append((mat.name, 'internal exporter error (please report): %s: %s'
                                  % (type(exc).__name__, exc)))
            continue
        lines = body.split('\n')
        # The header comment first, then the material statement.
        head_len = 0
        while head_len < len(lines) and lines[head_len].startswith('#'):
            head_len += 1
        text = '\n'.join(lines[:head_len] + ['material %s;' % name] + lines[head_len:])
        path = os.path.join(out_dir, name + '.mgraph')
        write_atomic(path, text)
        result.files.append(path)
        index[mat.name] = {'file': name + '.mgraph', 'material': name}
    write_atomic(os.path.join(out_dir, 'index.json'),
                 json.dumps({'materials': index}, indent=2, sort_keys=True) + '\n')
    return result
