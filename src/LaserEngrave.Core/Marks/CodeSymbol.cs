using QRCoder;
using ZXing;
using ZXing.Datamatrix;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Marks;

/// <summary>A code's modules, one pixel a module, without its quiet zone: a set bit is a dark module (burned).</summary>
public sealed record CodeSymbol(CodeKind Kind, string Text, BitMask Modules)
{
    /// <summary>The longest text a code may carry here: sample IDs are short, and a long one makes modules too small to burn.</summary>
    public const int MaxTextLength = 500;

    /// <summary>Modules per side.</summary>
    public int Size => Modules.Width;

    /// <summary>Encodes <paramref name="text"/>; <paramref name="errorCorrection"/> is L, M, Q or H for a QR code and must be null for a Data Matrix.</summary>
    /// <exception cref="MarkException">The text is empty, too long or not encodable, or the level is not one the code has.</exception>
    public static CodeSymbol Encode(CodeKind kind, string text, char? errorCorrection = null)
    {
        ArgumentNullException.ThrowIfNull(text);
        if (text.Length == 0)
        {
            throw new MarkException("the code's text is empty");
        }

        if (text.Length > MaxTextLength)
        {
            throw new MarkException($"the code's text has {text.Length} characters, more than the {MaxTextLength} a mark may carry");
        }

        return kind switch
        {
            CodeKind.Qr => Qr(text, errorCorrection ?? 'M'),
            CodeKind.DataMatrix => errorCorrection is null
                ? DataMatrix(text)
                : throw new MarkException($"error correction {errorCorrection} is for QR codes; a Data Matrix (ECC 200) has its own, fixed by its size"),
            _ => throw new ArgumentOutOfRangeException(nameof(kind)),
        };
    }

    private static CodeSymbol Qr(string text, char level)
    {
        var ecc = char.ToUpperInvariant(level) switch
        {
            'L' => QRCodeGenerator.ECCLevel.L,
            'M' => QRCodeGenerator.ECCLevel.M,
            'Q' => QRCodeGenerator.ECCLevel.Q,
            'H' => QRCodeGenerator.ECCLevel.H,
            _ => throw new MarkException($"error correction \"{level}\" is not L, M, Q or H"),
        };
        QRCodeData data;
        try
        {
            data = QRCodeGenerator.GenerateQrCode(text, ecc);
        }
        catch (Exception ex) when (ex is QRCoder.Exceptions.DataTooLongException or ArgumentException)
        {
            throw new MarkException($"\"{Shorten(text)}\" does not fit a QR code at level {char.ToUpperInvariant(level)}: {ex.Message}", ex);
        }

        // QRCoder's matrix carries a 4-module quiet zone on each side; the mark's own quiet zone replaces it.
        const int quiet = 4;
        var size = data.ModuleMatrix.Count - (2 * quiet);
        var modules = new BitMask(size, size);
        for (var y = 0; y < size; y++)
        {
            var row = data.ModuleMatrix[y + quiet];
            for (var x = 0; x < size; x++)
            {
                modules[x, y] = row[x + quiet];
            }
        }

        return new CodeSymbol(CodeKind.Qr, text, modules);
    }

    private static CodeSymbol DataMatrix(string text)
    {
        if (text.Any(c => c > 255))
        {
            throw new MarkException($"\"{Shorten(text)}\" has characters a Data Matrix cannot carry here (Latin-1 only)");
        }

        var hints = new Dictionary<EncodeHintType, object> { [EncodeHintType.DATA_MATRIX_SHAPE] = ZXing.Datamatrix.Encoder.SymbolShapeHint.FORCE_SQUARE };
        ZXing.Common.BitMatrix matrix;
        try
        {
            // Width and height 0: ZXing returns the symbol at one pixel a module.
            matrix = new DataMatrixWriter().encode(text, BarcodeFormat.DATA_MATRIX, 0, 0, hints);
        }
        catch (Exception ex) when (ex is ArgumentException or InvalidOperationException or WriterException)
        {
            throw new MarkException($"\"{Shorten(text)}\" does not fit a Data Matrix: {ex.Message}", ex);
        }

        var modules = new BitMask(matrix.Width, matrix.Height);
        for (var y = 0; y < matrix.Height; y++)
        {
            for (var x = 0; x < matrix.Width; x++)
            {
                modules[x, y] = matrix[x, y];
            }
        }

        return new CodeSymbol(CodeKind.DataMatrix, text, modules);
    }

    private static string Shorten(string text) => text.Length <= 40 ? text : text[..37] + "...";
}
