"""One glTF 2.0 buffer being built (sections 3.6.1-3.6.2: buffers, buffer views, accessors), shared
by the content generators (make_skin_content.py, make_level_content.py): each view starts on a
4-byte boundary, as an accessor of floats must."""


class GltfBuffer:
    def __init__(self):
        self.blob, self.views, self.accessors = bytearray(), [], []

    def add(self, data, count, type_, ctype, minmax=None, target=None):
        """Appends `data` as a new buffer view with one accessor over it (`count` elements of `type_`,
        component type `ctype`, optional (min, max) and view target); returns the accessor's index."""
        while len(self.blob) % 4:
            self.blob.append(0)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        self.views.append(view)
        self.blob.extend(data)
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": count, "type": type_}
        if minmax:
            acc["min"], acc["max"] = minmax
        self.accessors.append(acc)
        return len(self.accessors) - 1
