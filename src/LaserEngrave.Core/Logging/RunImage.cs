namespace LaserEngrave.Core.Logging;

/// <summary>The image a run engraved: where it was, its SHA-256 (to refuse repeating a run on a changed file) and its size.</summary>
/// <param name="Path">The full path of the image file at the time of the run.</param>
/// <param name="Sha256">SHA-256 of the file's bytes, lower-case hex.</param>
/// <param name="WidthPx">Width of the image (and of the mask), pixels.</param>
/// <param name="HeightPx">Height of the image (and of the mask), pixels.</param>
public sealed record RunImage(string Path, string Sha256, int WidthPx, int HeightPx);
