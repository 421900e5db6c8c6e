namespace LaserEngrave.Core.Marks;

/// <summary>One copy of a mark as made: its number, its resolved text and where it lies on the stage (mm, top left and size of what burns).</summary>
/// <param name="Number">The copy's number.</param>
/// <param name="Text">The text with its placeholders resolved.</param>
/// <param name="Kind">"qr", "datamatrix" or "text".</param>
/// <param name="XMm">Left edge of the code's symbol (or of the text).</param>
/// <param name="YMm">Top edge.</param>
/// <param name="WidthMm">The symbol's (or the text's) width.</param>
/// <param name="HeightMm">Its height.</param>
/// <param name="ModuleUm">A code's module, µm; null for a text.</param>
public sealed record PlacedMark(int Number, string Text, string Kind, double XMm, double YMm, double WidthMm, double HeightMm, double? ModuleUm);
