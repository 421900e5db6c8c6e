namespace LaserEngrave.Core.Imaging;

/// <summary>Decodes the first frame of a GIF onto its canvas: LZW, global or local colour table, transparency, interlacing.</summary>
/// <remarks>Our own decoder because SixLabors.ImageSharp is not on this machine's package source.</remarks>
internal static class GifDecoder
{
    /// <summary>No LZW code can stand for more indices than the 4096-entry table holds.</summary>
    private const long MaxIndicesPerCode = 4096;

    public static ImageInfo ReadInfo(ImageReader reader) => GifHeader.Read(reader).ToInfo(reader.Path, reader.Length);

    public static LoadedImage Decode(ImageReader reader)
    {
        var gif = GifHeader.Read(reader);
        var info = gif.ToInfo(reader.Path, reader.Length);
        int canvasWidth = gif.CanvasWidth, canvasHeight = gif.CanvasHeight;
        ImageLimits.CheckIndexed(reader.Path, canvasWidth, canvasHeight, 8);

        reader.Position = gif.DataOffset;
        int minCodeSize = reader.ReadByte("the GIF LZW code size");
        var dataStart = reader.Position;
        var dataBytes = GifHeader.SkipSubBlocks(reader);
        long framePixels = (long)gif.FrameWidth * gif.FrameHeight;
        if (framePixels > dataBytes * 8 / (minCodeSize + 1) * MaxIndicesPerCode)
        {
            throw reader.Fail($"the GIF's {dataBytes} bytes of image data cannot hold a {gif.FrameWidth} x {gif.FrameHeight} frame; the file is truncated or its header is wrong");
        }

        var data = new byte[dataBytes];
        reader.Position = dataStart;
        var filled = 0;
        while (true)
        {
            var size = reader.ReadByte("GIF data sub-blocks");
            if (size == 0)
            {
                break;
            }

            reader.ReadExactly(data.AsSpan(filled, size), "a GIF data sub-block");
            filled += size;
        }

        var frame = new byte[framePixels];
        GifLzwDecoder.Decode(reader, data, minCodeSize, frame);
        var bad = gif.Palette.Length < 256 ? frame.AsSpan().IndexOfAnyInRange((byte)gif.Palette.Length, byte.MaxValue) : -1;
        if (bad >= 0)
        {
            throw reader.Fail($"a GIF pixel uses colour index {frame[bad]}, but the colour table has only {gif.Palette.Length} colours");
        }

        var palette = (Rgba32[])gif.Palette.Clone();
        if (gif.TransparentIndex >= 0)
        {
            palette[gif.TransparentIndex] = palette[gif.TransparentIndex] with { A = 0 };
        }

        if (gif.FrameCoversCanvas && !gif.Interlaced)
        {
            return LoadedImage.Indexed(info, canvasWidth, canvasHeight, 8, palette, frame);
        }

        // The canvas outside the frame is transparent: the frame's own transparent index, else one added to the palette.
        var fill = gif.TransparentIndex >= 0 ? gif.TransparentIndex : palette.Length;
        if (!gif.FrameCoversCanvas && fill == palette.Length)
        {
            if (palette.Length == 256)
            {
                return ToRgbaCanvas(reader, gif, info, palette, frame);
            }

            palette = [.. palette, Rgba32.Transparent];
        }

        var canvas = new byte[(long)canvasWidth * canvasHeight];
        if (!gif.FrameCoversCanvas)
        {
            Array.Fill(canvas, (byte)fill);
        }

        for (var row = 0; row < gif.FrameHeight; row++)
        {
            var y = gif.Top + FrameRow(row, gif.FrameHeight, gif.Interlaced);
            frame.AsSpan(row * gif.FrameWidth, gif.FrameWidth).CopyTo(canvas.AsSpan((int)(((long)y * canvasWidth) + gif.Left)));
        }

        return LoadedImage.Indexed(info, canvasWidth, canvasHeight, 8, palette, canvas);
    }

    /// <summary>The image row that the <paramref name="stored"/>-th stored row belongs to (interlaced: every 8th from 0, from 4, every 4th from 2, every 2nd from 1).</summary>
    internal static int FrameRow(int stored, int height, bool interlaced)
    {
        if (!interlaced)
        {
            return stored;
        }

        int pass1 = (height + 7) / 8, pass2 = (height + 3) / 8, pass3 = (height + 1) / 4;
        if (stored < pass1)
        {
            return stored * 8;
        }

        stored -= pass1;
        if (stored < pass2)
        {
            return 4 + (stored * 8);
        }

        stored -= pass2;
        return stored < pass3 ? 2 + (stored * 4) : 1 + ((stored - pass3) * 2);
    }

    private static LoadedImage ToRgbaCanvas(ImageReader reader, GifHeader gif, ImageInfo info, Rgba32[] palette, byte[] frame)
    {
        ImageLimits.CheckFullColour(reader.Path, gif.CanvasWidth, gif.CanvasHeight);
        var rgba = new byte[(long)gif.CanvasWidth * gif.CanvasHeight * 4];
        for (var row = 0; row < gif.FrameHeight; row++)
        {
            var y = gif.Top + FrameRow(row, gif.FrameHeight, gif.Interlaced);
            for (var i = 0; i < gif.FrameWidth; i++)
            {
                var c = palette[frame[(row * gif.FrameWidth) + i]];
                var o = rgba.AsSpan((int)((((long)y * gif.CanvasWidth) + gif.Left + i) * 4), 4);
                (o[0], o[1], o[2], o[3]) = (c.R, c.G, c.B, c.A);
            }
        }

        return LoadedImage.Rgba(info, gif.CanvasWidth, gif.CanvasHeight, rgba);
    }
}
