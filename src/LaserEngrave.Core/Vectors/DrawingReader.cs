namespace LaserEngrave.Core.Vectors;

/// <summary>Reads a drawing by its file name: .dxf or .svg.</summary>
public static class DrawingReader
{
    /// <summary>Whether the file name says it is a drawing LaserEngrave reads (rather than an image).</summary>
    public static bool IsDrawing(string path) =>
        Path.GetExtension(path).ToLowerInvariant() is ".dxf" or ".svg";

    public static Drawing Read(string path) => Path.GetExtension(path).ToLowerInvariant() switch
    {
        ".dxf" => DxfReader.Read(path),
        ".svg" => SvgReader.Read(path),
        var other => throw new DrawingException($"{path}: \"{other}\" is not a drawing format; use .dxf or .svg"),
    };
}
