namespace LaserEngrave.Core.Imaging;

/// <summary>Receives one decoded row of an image, <paramref name="y"/> counted from the top, in the decoder's own pixel form.</summary>
internal delegate void RowHandler(int y, ReadOnlySpan<byte> row);
