using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>A marks file's values are refused at the edge in the file's words.</summary>
public sealed class MarkFileTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("le-markfile-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    [Theory]
    [InlineData("originMm")]
    [InlineData("pitchMm")]
    public void Load_PairBeyondDouble_IsRefusedAsNotMm(string field)
    {
        var path = Path.Combine(_folder, "marks.json");
        File.WriteAllText(path, $$"""{ "text": "S", "{{field}}": [1e400, 5] }""");

        var ex = Assert.Throws<MarkException>(() => MarkFile.Load(path));

        Assert.Contains($"\"{field}\" must be [x, y] in mm", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_TruncatedFile_IsRefusedInTheFilesWordsNotTheParsers()
    {
        var path = Path.Combine(_folder, "marks.json");
        File.WriteAllText(path, "{ \"text\": \"S\",\n  \"copies\": ");

        var ex = Assert.Throws<MarkException>(() => MarkFile.Load(path));

        Assert.StartsWith($"{path}: not a marks file: not valid JSON", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain("BytePositionInLine", ex.Message, StringComparison.Ordinal);
    }
}
