using System.Text;
using System.Text.Json;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.IO;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.IO;

/// <summary>The files a person writes read as UTF-8 (or UTF-16 with its BOM) or refused naming the line; JSON errors in their words, 1-based (issue 32, finding 10).</summary>
public sealed class TextFileTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("textfile-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    /// <summary>"Größe" as Windows-1252 writes it: ö = 0xF6, ß = 0xDF.</summary>
    private static byte[] Cp1252(string ascii, string before, string after) =>
        [.. Encoding.ASCII.GetBytes(ascii + before), (byte)'G', (byte)'r', 0xF6, 0xDF, (byte)'e', .. Encoding.ASCII.GetBytes(after)];

    private string Write(string name, byte[] bytes)
    {
        var path = Path.Combine(_folder, name);
        File.WriteAllBytes(path, bytes);
        return path;
    }

    private string Write(string name, string text) => Write(name, Encoding.UTF8.GetBytes(text));

    [Fact]
    public void Decode_Windows1252_RefusedNamingLineAndColumn()
    {
        var ex = Assert.Throws<TextEncodingException>(() => TextFile.Decode(Cp1252("{\n", "  \"name\": \"", "\"\n}")));

        Assert.StartsWith("line 2, column 14 is not UTF-8 text (byte 0xF6)", ex.Message, StringComparison.Ordinal);
        Assert.EndsWith("save the file as UTF-8", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("utf-8")]
    [InlineData("utf-8-bom")]
    [InlineData("utf-16le-bom")]
    [InlineData("utf-16be-bom")]
    public void Decode_UnicodeWithOrWithoutItsMark_ReadAsWritten(string encoding)
    {
        var bytes = encoding switch
        {
            "utf-8" => Encoding.UTF8.GetBytes("Größe µm"),
            "utf-8-bom" => [.. Encoding.UTF8.Preamble, .. Encoding.UTF8.GetBytes("Größe µm")],
            "utf-16le-bom" => [.. Encoding.Unicode.Preamble, .. Encoding.Unicode.GetBytes("Größe µm")],
            _ => [.. Encoding.BigEndianUnicode.Preamble, .. Encoding.BigEndianUnicode.GetBytes("Größe µm")],
        };

        Assert.Equal("Größe µm", TextFile.Decode(bytes));
    }

    [Fact]
    public void JobFileLoad_Windows1252Name_RefusedNamingTheLineNotMangled()
    {
        var path = Write("job.json", Cp1252("{ \"layers\": [\n", "  { \"source\": \"a.png\", \"name\": \"", "\" }\n] }\n"));

        var ex = Assert.Throws<PlanException>(() => JobFile.Load(path));

        Assert.Equal($"{path}: line 2, column 35 is not UTF-8 text (byte 0xF6) (it looks like Windows-1252 or Latin-1, e.g. ö or ß saved by an older editor): save the file as UTF-8", ex.Message);
    }

    [Fact]
    public void JobFileLoad_Utf16WithBom_Read()
    {
        var path = Write("job.json", [.. Encoding.Unicode.Preamble, .. Encoding.Unicode.GetBytes("{ \"layers\": [ { \"source\": \"a.svg\", \"name\": \"Größe\" } ] }")]);

        Assert.Equal("Größe", Assert.Single(JobFile.Load(path)).Name);
    }

    [Theory]
    [InlineData("{ \"layers\": [\n  { \"source\": \"a.png\" }\n  { \"source\": \"b.png\" }\n] }", "not valid JSON at line 3, column 3: '{' where a comma or a closing bracket belongs: a comma is missing before it, or a bracket is too many")]
    [InlineData("{ \"layers\": [\n  { source: \"a.png\" }\n] }", "not valid JSON at line 2, column 5: a field's name goes in double quotes")]
    [InlineData("{ \"layers\": [\n  { \"source\": 'a.png' }\n] }", "not valid JSON at line 2, column 15: ''' cannot begin a value (text goes in double quotes")]
    [InlineData("{ \"layers\": [\n  { \"source\": \"a.png\" }\n", "not valid JSON at line 3, column 1: the file ends before every { and [ is closed")]
    public void JobFileLoad_NotJson_WhereAndWhatInWordsFromLineOne(string json, string expected)
    {
        var path = Write("job.json", json);

        var ex = Assert.Throws<PlanException>(() => JobFile.Load(path));

        Assert.StartsWith($"{path}: {expected}", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain("LineNumber", ex.Message, StringComparison.Ordinal);
        Assert.DoesNotContain("BytePositionInLine", ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("\"12,5\"", "\"speedMmPerS\" must be a number: write 12.5, without quotes")]
    [InlineData("\"1,000\"", "\"speedMmPerS\" must be a number (\"1,000\" could be 1 or 1000: write 1000 or 1.0, without quotes)")]
    public void JobFileLoad_NumberAsText_HowToWriteIt(string value, string expected)
    {
        var path = Write("job.json", $"{{ \"layers\": [ {{ \"source\": \"a.png\", \"speedMmPerS\": {value} }} ] }}");

        var ex = Assert.Throws<PlanException>(() => JobFile.Load(path));

        Assert.EndsWith(expected, ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("{\n  \"burnSpeedMmPerS\": \"12,5\"\n}", "burnSpeedMmPerS has a value of the wrong type or out of range for it (line 2, column ", ": write 12.5 as a number, without quotes")]
    [InlineData("{ \"gate\": {\n  \"watchdogMs\": \"1.000\" } }", "gate.watchdogMs has a value of the wrong type or out of range for it (line 2, column ", ": \"1.000\" could be 1 or 1000: write 1000 or 1.0, as a number without quotes")]
    [InlineData("{ \"scanOffsets\": [ { \"speedMmPerS\": 1, \"offsetUm\": \"0,5\" } ] }", "scanOffsets[0].offsetUm has a value of the wrong type", ": write 0.5 as a number, without quotes")]
    public void ProfileLoad_DecimalCommaText_HintHowToWriteIt(string json, string starts, string ends)
    {
        var path = Write("profile.json", json);

        var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));

        Assert.Contains(starts, ex.Message, StringComparison.Ordinal);
        Assert.EndsWith(ends, ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void ProfileLoad_Windows1252_RefusedNamingTheLine()
    {
        var path = Write("profile.json", Cp1252("{\n", "  \"name\": \"", "\"\n}"));

        var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));

        Assert.StartsWith($"{path}: line 2, column 14 is not UTF-8 text", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void ProfileLoad_MissingComma_SaysWhereInWords()
    {
        var path = Write("profile.json", "{\n  \"name\": \"lab\"\n  \"burnSpeedMmPerS\": 1\n}");

        var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));

        Assert.Equal($"{path}: not valid JSON at line 3, column 3: '\"' where a comma or a closing bracket belongs: a comma is missing before it, or a bracket is too many", ex.Message);
    }

    [Fact]
    public void RunLogRead_Windows1252_RefusedNamingTheLine()
    {
        var path = Write("run.json", Cp1252("{\n", "\"notes\": \"", "\"}"));

        var ex = Assert.Throws<RunLogException>(() => RunLogStore.Read(path));

        Assert.StartsWith($"{path}: line 2, column 13 is not UTF-8 text", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void Describe_WrongTypeDeepInALog_OneBasedLineAndColumn()
    {
        var ex = Assert.Throws<JsonException>(() => JsonSerializer.Deserialize<Dictionary<string, int>>("{\n  \"a\": 1,\n  \"b\": \"x\"\n}"));

        Assert.Equal("not a run log: b has a value of the wrong type or out of range for it (line 3, column 11)", JsonProblem.Describe(ex, "run log"));
    }
}
